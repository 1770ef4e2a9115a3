// The Householder basis (1-linalg/householder_basis.hpp) against what it claims, checked with
// products of explicit matrices: [Q₁ Q₂] orthogonal, Q₂ orthogonal to the columns of A (so Q₁ spans
// them), and transformSimilar equal to Qᵀ X Q; on random A with orthonormal columns (the V₁ of a
// constraint Jacobian) and on general ones, of the sizes a Newmark step meets.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <random>

#include "mbsopt/linalg/householder_basis.hpp"
#include "tests/random_matrices.hpp"

namespace mbsopt {
namespace {

using test_support::kEpsilon;
using test_support::randomMatrix;

/// Q₂ orthonormal and orthogonal to A, and Q₂ and Qᵀ X Q against the explicit Q of Eigen's
/// HouseholderQR, an independent implementation with the same sign convention (β = −sign(x_k)‖x‖).
void expectBasisOf(const Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows(), r = a.cols();
  HouseholderBasis basis;
  basis.compute(a);
  ASSERT_EQ(basis.reflectorCount(), r);
  Eigen::MatrixXd q2;
  basis.complement(q2);
  ASSERT_EQ(q2.rows(), n);
  ASSERT_EQ(q2.cols(), n - r);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  if (n > r) {  // Q₂ orthonormal, and orthogonal to every column of A: a few ε (each reflector is backward stable)
    EXPECT_LT((q2.transpose() * q2 - Eigen::MatrixXd::Identity(n - r, n - r)).cwiseAbs().maxCoeff(), 50 * kEpsilon);
    EXPECT_LT((a.transpose() * q2).cwiseAbs().maxCoeff(), 50 * kEpsilon * a.norm());
    EXPECT_LT((q.rightCols(n - r) - q2).cwiseAbs().maxCoeff(), 50 * kEpsilon);
  }
  std::mt19937 generator(static_cast<unsigned>(n * 100 + r));
  const Eigen::MatrixXd x = randomMatrix(n, n, generator);
  Eigen::MatrixXd transformed = x;
  basis.transformSimilar(transformed);
  EXPECT_LT((transformed - q.transpose() * x * q).cwiseAbs().maxCoeff(), 50 * kEpsilon * n);
}

TEST(HouseholderBasis, CompletesOrthonormalColumnsToAnOrthonormalBasis) {
  std::mt19937 generator(21);
  for (const auto& [n, r] : {std::pair{5, 2}, std::pair{5, 3}, std::pair{3, 3}, std::pair{64, 3}, std::pair{40, 12},
                             std::pair{1, 1}, std::pair{6, 1}})
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::MatrixXd orthonormal = Eigen::HouseholderQR<Eigen::MatrixXd>(randomMatrix(n, r, generator))
                                              .householderQ() * Eigen::MatrixXd::Identity(n, r);
      expectBasisOf(orthonormal);
      expectBasisOf(randomMatrix(n, r, generator));  // any full column rank works the same way
    }
}

// A column that is already a multiple of e_k needs no reflection (τ = 0): the basis must still be
// the identity's complement, and no division by a zero tail may occur.
TEST(HouseholderBasis, LeavesColumnsAlongTheAxesAlone) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 2);
  a(0, 0) = 2.0;
  a(1, 1) = -3.0;
  HouseholderBasis basis;
  basis.compute(a);
  Eigen::MatrixXd q2;
  basis.complement(q2);
  EXPECT_EQ(q2, Eigen::MatrixXd::Identity(4, 4).rightCols(2));
}

}  // namespace
}  // namespace mbsopt
