// The one-sided Jacobi SVD (1-linalg/one_sided_jacobi.hpp) against what it claims, A W = X Σ with W
// orthogonal and the columns of X Σ mutually orthogonal, and its singular values against Eigen's
// two-sided JacobiSVD (an independent computation): on random matrices of the shapes the constraint
// Jacobians take (tall, square, wide), rank-deficient ones, and column-graded ones whose small
// singular values both methods determine to high relative accuracy (Demmel and Veselić 1992).
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <random>

#include "mbsopt/linalg/one_sided_jacobi.hpp"
#include "tests/random_matrices.hpp"

namespace mbsopt {
namespace {

using test_support::kEpsilon;
using test_support::randomMatrix;

/// The decomposition's identities, each to a few hundred ε of ‖A‖ (backward stability of plane
/// rotations: each sweep adds O(cols · ε) relative error to every column), and the stopping test's
/// orthogonality, √rows · ε relative, with the round-off of the last rotations.
void expectDecomposition(const Eigen::MatrixXd& a, const OneSidedJacobiSvd& svd) {
  const Eigen::Index cols = a.cols();
  const double scale = a.norm();
  const Eigen::MatrixXd& w = svd.rotations();
  const Eigen::MatrixXd& x = svd.orthogonalColumns();
  const Eigen::VectorXd& sigma = svd.singularValues();
  ASSERT_EQ(sigma.size(), cols);
  EXPECT_LT(svd.sweeps(), OneSidedJacobiSvd::kMaxSweeps);
  EXPECT_LT((w.transpose() * w - Eigen::MatrixXd::Identity(cols, cols)).cwiseAbs().maxCoeff(), 200 * kEpsilon);
  EXPECT_LT((a * w - x).cwiseAbs().maxCoeff(), 200 * kEpsilon * scale);
  for (Eigen::Index j = 0; j < cols; ++j) {
    EXPECT_NEAR(x.col(j).norm(), sigma[j], 200 * kEpsilon * scale);
    if (j > 0) {
      EXPECT_LE(sigma[j], sigma[j - 1]);
    }
    // Mutually orthogonal relative to their norms; a column at the round-off level of ‖A‖ (a rank
    // deficiency) has no direction to speak of: its size is what expectSingularValuesOf checks.
    if (sigma[j] <= 100 * kEpsilon * scale) continue;
    for (Eigen::Index i = 0; i < j; ++i)
      EXPECT_LE(std::abs(x.col(i).dot(x.col(j))), 200 * kEpsilon * sigma[i] * sigma[j]) << i << ", " << j;
  }
}

/// Σ against Eigen's JacobiSVD: min(rows, cols) values to `relative`, or to the round-off of ‖A‖ that a
/// backward-stable method leaves in any singular value (Weyl); the rest (a wide A) round-off of ‖A‖.
void expectSingularValuesOf(const Eigen::MatrixXd& a, const OneSidedJacobiSvd& svd, double relative) {
  const Eigen::VectorXd reference = Eigen::JacobiSVD<Eigen::MatrixXd>(a).singularValues();
  const Eigen::VectorXd& sigma = svd.singularValues();
  for (Eigen::Index j = 0; j < reference.size(); ++j)
    EXPECT_NEAR(sigma[j], reference[j], relative * reference[j] + 200 * kEpsilon * a.norm()) << "σ" << j;
  for (Eigen::Index j = reference.size(); j < sigma.size(); ++j) EXPECT_LT(sigma[j], 200 * kEpsilon * a.norm());
}

TEST(OneSidedJacobiSvd, DecomposesRandomMatricesOfEveryShape) {
  std::mt19937 generator(11);
  OneSidedJacobiSvd svd;  // one object for all: buffers resized between shapes
  for (const auto& [rows, cols] : {std::pair{5, 3}, std::pair{3, 3}, std::pair{2, 5}, std::pair{64, 3}, std::pair{40, 12},
                                   std::pair{1, 1}, std::pair{7, 1}}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::MatrixXd a = randomMatrix(rows, cols, generator);
      svd.compute(a);
      expectDecomposition(a, svd);
      // A well-conditioned random A: every singular value to a few hundred ε relative.
      expectSingularValuesOf(a, svd, 1e-13);
    }
  }
}

// A column that depends on two others, and an exactly zero column (the in-plane tram's closure row
// that is identically zero): the rank shows as singular values at round-off.
TEST(OneSidedJacobiSvd, ShowsTheRankOfDeficientMatrices) {
  std::mt19937 generator(12);
  OneSidedJacobiSvd svd;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::MatrixXd a = randomMatrix(6, 4, generator);
    a.col(3) = 0.5 * a.col(0) - 2.0 * a.col(1);
    a.col(2).setZero();
    svd.compute(a);
    expectDecomposition(a, svd);
    expectSingularValuesOf(a, svd, 1e-13);
    EXPECT_GT(svd.singularValues()[1], 1e-3 * svd.singularValues()[0]);
    EXPECT_LT(svd.singularValues()[2], 1e-14 * svd.singularValues()[0]);
    EXPECT_EQ(svd.singularValues()[3], 0.0);
  }
}

// A = B D with B random (κ(B) ≲ 1e2) and D = diag(1, 1e-5, 1e-10): its singular values are fixed
// to relative accuracy ε κ(B) by the data, and both methods find them so (the QR-preconditioned
// two-sided Jacobi of Eigen as well); a method accurate only to ε σ_max would miss the smallest by 1e-6.
TEST(OneSidedJacobiSvd, ResolvesTheSmallSingularValuesOfGradedMatrices) {
  std::mt19937 generator(13);
  OneSidedJacobiSvd svd;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXd b = randomMatrix(8, 3, generator);
    const Eigen::MatrixXd a = b * Eigen::Vector3d(1.0, 1e-5, 1e-10).asDiagonal();
    svd.compute(a);
    expectDecomposition(a, svd);
    const Eigen::VectorXd reference = Eigen::JacobiSVD<Eigen::MatrixXd>(a).singularValues();
    for (Eigen::Index j = 0; j < 3; ++j) EXPECT_NEAR(svd.singularValues()[j], reference[j], 1e-11 * reference[j]);
  }
}

// The minimum-norm least-squares solution against Eigen's complete orthogonal decomposition (an
// independent method), on tall full-rank systems and on rank-deficient ones with an inconsistent
// right-hand side, where only the minimum-norm solution is unique.
TEST(OneSidedJacobiSvd, SolvesLeastSquaresWithMinimumNorm) {
  std::mt19937 generator(14);
  OneSidedJacobiSvd svd;
  Eigen::VectorXd x, work;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::MatrixXd a = randomMatrix(7, 4, generator);
    if (trial % 2 == 1) a.col(3) = a.col(0) - 0.5 * a.col(2);  // rank 3
    const Eigen::VectorXd b = randomMatrix(7, 1, generator);
    svd.compute(a);
    svd.solveLeastSquares(b, 1e-8, x, work);
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> reference(a);
    reference.setThreshold(1e-8);
    const Eigen::VectorXd expected = reference.solve(b);
    // Both backward stable on systems with κ ≲ 1e2 over the kept range: agreement to 1e-12.
    EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm()) << "trial " << trial;
  }
}

// A(t) = A₀ + t A₁ at steps of 1e-3, as a constraint Jacobian moves from one Newmark step to the
// next, decomposed by update() from the last W: every decomposition as compute()'s is (identities,
// singular values against Eigen's), W orthogonal to the same 200 ε over 300 updates (through the
// cold restarts that bound its drift), and fewer sweeps than from I: the columns of A W start
// orthogonal to O(1e-3), and the sweeps converge quadratically (cold: O(1) off-diagonal to start).
// A matrix of other sizes starts from I.
/// kCount matrices 7 × 6, 1e-3 of a random direction apart, as a Newmark step's constraint Jacobians.
struct NearbyMatrices {
  static constexpr int kCount = 300;
  explicit NearbyMatrices(std::mt19937& generator)
      : start(randomMatrix(7, 6, generator)), direction(randomMatrix(7, 6, generator)) {}
  Eigen::MatrixXd operator[](int k) const { return start + 1e-3 * k * direction; }
  Eigen::MatrixXd start, direction;
};

TEST(OneSidedJacobiSvd, UpdatesANearbyMatrixFromTheLastRotationsInFewerSweeps) {
  std::mt19937 generator(15);
  const NearbyMatrices matrices(generator);
  OneSidedJacobiSvd warm, cold;
  int warm_sweeps = 0, cold_sweeps = 0;
  for (int k = 0; k < NearbyMatrices::kCount; ++k) {
    const Eigen::MatrixXd a = matrices[k];
    warm.update(a);
    cold.compute(a);
    expectDecomposition(a, warm);
    expectSingularValuesOf(a, warm, 1e-13);
    if (k % OneSidedJacobiSvd::kWarmStartsBeforeCold != 0) {
      warm_sweeps += warm.sweeps();
      cold_sweeps += cold.sweeps();
    }
  }
  EXPECT_LT(warm_sweeps, 0.75 * cold_sweeps);
  const Eigen::MatrixXd other = randomMatrix(5, 3, generator);
  warm.update(other);
  cold.compute(other);
  EXPECT_EQ(warm.singularValues(), cold.singularValues());  // the same arithmetic from I
}

TEST(OneSidedJacobiSvd, UpdatesToAStatedOrthogonalityInFewerSweeps) {
  // update(a, τ) stops when every pair of columns is orthogonal to τ relative to their norms: W stays
  // orthogonal and A W = X to round-off as before (the rotations are exact whatever their number),
  // the columns' products stay within τ of zero, and Σ moves only at second order in τ (the Gram
  // matrix's off-diagonal τ σᵢσⱼ shifts its eigenvalues by τ² σᵢ²σⱼ²/(σᵢ² − σⱼ²)): 1e-12 relative.
  constexpr double tau = 1e-8;
  std::mt19937 generator(15);
  const NearbyMatrices matrices(generator);
  OneSidedJacobiSvd relaxed, exact;
  int relaxed_sweeps = 0, exact_sweeps = 0;
  for (int k = 0; k < NearbyMatrices::kCount; ++k) {
    const Eigen::MatrixXd a = matrices[k];
    relaxed.update(a, tau);
    exact.update(a);
    relaxed_sweeps += relaxed.sweeps();
    exact_sweeps += exact.sweeps();
    const Eigen::MatrixXd& w = relaxed.rotations();
    const Eigen::MatrixXd& x = relaxed.orthogonalColumns();
    const Eigen::VectorXd& sigma = relaxed.singularValues();
    EXPECT_LT((w.transpose() * w - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), 200 * kEpsilon);
    EXPECT_LT((a * w - x).cwiseAbs().maxCoeff(), 200 * kEpsilon * a.norm());
    for (Eigen::Index j = 1; j < 6; ++j)
      for (Eigen::Index i = 0; i < j; ++i)
        EXPECT_LE(std::abs(x.col(i).dot(x.col(j))), (tau + 200 * kEpsilon) * sigma[i] * sigma[j]) << k;
    expectSingularValuesOf(a, relaxed, 1e-12);
  }
  EXPECT_LT(relaxed_sweeps, 0.9 * exact_sweeps);
}

}  // namespace
}  // namespace mbsopt
