// The augmented solve of SvdPartition (3-algorithms/svd_partition.hpp) against the equations it
// solves, [J Bᵀ; B 0][Δx; Δμ] = −[r; g], on random systems with consistent right-hand sides: full
// row rank and with a dependent row, with few coordinates (V₂ᵀ J V₂ from the explicit V₂) and with
// many (from the Householder reflectors of V₁). The residuals must vanish to round-off; and so
// must those of the projection, the system with r = 0 solved without its multipliers. With a
// dependent row the multipliers are not unique: the partition's must be those of minimum norm.
// Several right-hand sides at once give what one solve per column gives, to the bit, and copied
// factors what the partition that computed them gives. The small
// products it is built from (1-linalg/small_products.hpp) against Eigen's.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <limits>
#include <random>

#include "mbsopt/linalg/small_products.hpp"
#include "mbsopt/algorithms/articulated_body.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/mass_matrix.hpp"
#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/algorithms/tangent.hpp"
#include "mbsopt/design/chain_scenes.hpp"
#include "tests/random_matrices.hpp"

namespace mbsopt {
namespace {

struct System {
  Eigen::MatrixXd J, B;
  Eigen::VectorXd r, g;
};

/// J = AᵀA + I (n × n, well conditioned), B m × n random with its last row `dependent` on the first
/// two when asked, g = B x₀ (consistent: in the range of B).
System randomSystem(Eigen::Index n, Eigen::Index m, bool dependent, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  const auto random = [&](Eigen::Index rows, Eigen::Index cols) {
    return Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return entry(generator); }).eval();
  };
  System s;
  const Eigen::MatrixXd a = random(n, n);
  s.J = a.transpose() * a + Eigen::MatrixXd::Identity(n, n);
  s.B = random(m, n);
  if (dependent) s.B.row(m - 1) = 0.5 * s.B.row(0) - 2.0 * s.B.row(1);
  s.r = random(n, 1);
  s.g = s.B * random(n, 1);
  return s;
}

void expectSolves(const System& s, int expected_rank) {
  SvdPartition partition(1e-8);
  partition.setConstraintJacobian(s.B);
  ASSERT_EQ(partition.rank(), expected_rank);
  const Eigen::MatrixXd& v2 = partition.freeDirections();
  const Eigen::Index n = s.J.rows();
  // V₂: orthonormal, and B does not move along it.
  EXPECT_LT((v2.transpose() * v2 - Eigen::MatrixXd::Identity(v2.cols(), v2.cols())).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((s.B * v2).cwiseAbs().maxCoeff(), 1e-13 * s.B.norm());
  ASSERT_TRUE(partition.setIterationMatrix(s.J));
  Eigen::VectorXd dx, dmu;
  partition.solve(s.r, s.g, dx, dmu);
  // Backward errors, relative to the data: a few hundred ε for these condition numbers (κ(J) ≲ 1e4).
  const double scale = s.J.norm() * dx.norm() + s.B.norm() * dmu.norm() + s.r.norm();
  EXPECT_LT((s.J * dx + s.B.transpose() * dmu + s.r).norm(), 1e-12 * scale) << "n = " << n;
  EXPECT_LT((s.B * dx + s.g).norm(), 1e-12 * (s.B.norm() * dx.norm() + s.g.norm())) << "n = " << n;
  // Minimum norm: no component along the kernel of Bᵀ (the combinations of rows that vanish, from an
  // LU of Bᵀ with full pivoting, independent of the SVD), along which Bᵀ Δμ would not change.
  const Eigen::MatrixXd kernel = Eigen::FullPivLU<Eigen::MatrixXd>(s.B.transpose()).kernel();
  if (expected_rank < s.B.rows()) {
    ASSERT_EQ(kernel.cols(), s.B.rows() - expected_rank);
    EXPECT_LT((kernel.transpose() * dmu).norm(), 1e-12 * kernel.norm() * dmu.norm()) << "n = " << n;
  }
  // The projection (r = 0, no multipliers): B Δ = −g, and J Δ in the range of Bᵀ (V₂ᵀ J Δ = 0), the
  // first row of the system with some multipliers.
  Eigen::VectorXd projection;
  partition.project(s.g, projection);
  EXPECT_LT((s.B * projection + s.g).norm(), 1e-12 * (s.B.norm() * projection.norm() + s.g.norm())) << "n = " << n;
  EXPECT_LT((v2.transpose() * s.J * projection).norm(), 1e-12 * s.J.norm() * projection.norm()) << "n = " << n;
}

TEST(SvdPartition, SolvesTheAugmentedSystemWithFewCoordinates) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    expectSolves(randomSystem(5, 3, false, seed), 3);
    expectSolves(randomSystem(5, 3, true, seed), 2);
  }
}

TEST(SvdPartition, SolvesTheAugmentedSystemWithManyCoordinates) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    expectSolves(randomSystem(40, 3, false, seed), 3);
    expectSolves(randomSystem(40, 6, true, seed), 5);
    expectSolves(randomSystem(64, 12, false, seed), 12);
  }
}

// Several right-hand sides at once (solveColumns, the exact gradients' sweeps): the same operations
// in the same order as one solve() per column, so the same bits, with and without the multipliers,
// and with G = 0 through its own overload; on few and many coordinates, with a dependent row, and
// without constraints.
void expectColumnsAsSolves(const SvdPartition& partition, const Eigen::MatrixXd& R, const Eigen::MatrixXd& G) {
  Eigen::MatrixXd dx, dmu, dx_alone;
  partition.solveColumns(R, G, dx, &dmu);
  partition.solveColumns(R, G, dx_alone, nullptr);
  ASSERT_EQ(dx.cols(), R.cols());
  ASSERT_EQ(dmu.rows(), G.rows());
  for (Eigen::Index j = 0; j < R.cols(); ++j) {
    Eigen::VectorXd column_dx, column_dmu;
    partition.solve(R.col(j), G.col(j), column_dx, column_dmu);
    EXPECT_TRUE(dx.col(j) == column_dx) << "column " << j << " of " << R.rows() << " coordinates";
    EXPECT_TRUE(dx_alone.col(j) == column_dx) << "column " << j << " without multipliers";
    EXPECT_TRUE(dmu.col(j) == column_dmu) << "column " << j;
  }
  // With G = 0, as in the adjoint's transposed solves: the overload that skips the products of the
  // range coordinates (zeros) gives the general solve's bits.
  Eigen::MatrixXd homogeneous_dx, homogeneous_dmu, general_dx, general_dmu;
  partition.solveColumns(R, homogeneous_dx, homogeneous_dmu);
  partition.solveColumns(R, Eigen::MatrixXd::Zero(G.rows(), G.cols()), general_dx, &general_dmu);
  EXPECT_TRUE(homogeneous_dx == general_dx) << R.rows() << " coordinates, G = 0";
  EXPECT_TRUE(homogeneous_dmu == general_dmu) << R.rows() << " coordinates, G = 0";
}

TEST(SvdPartition, SolvesColumnsBitForBitAsItSolvesEachColumn) {
  struct Case {
    Eigen::Index n, m;
    bool dependent;
  };
  // Case{3, 3, false}: B square and regular, no free direction left (V₂ has no column).
  for (const Case c : {Case{5, 3, false}, Case{5, 3, true}, Case{40, 6, true}, Case{30, 0, false}, Case{3, 3, false}})
    for (unsigned seed = 1; seed <= 5; ++seed) {
      SvdPartition partition(1e-8);
      const System s = randomSystem(c.n, c.m, c.dependent, seed);
      partition.setConstraintJacobian(s.B);
      ASSERT_TRUE(partition.setIterationMatrix(s.J));
      Eigen::MatrixXd R(c.n, 4), G(c.m, 4);
      for (Eigen::Index j = 0; j < 4; ++j) {
        const System other = randomSystem(c.n, c.m, c.dependent, 100 * seed + static_cast<unsigned>(j));
        R.col(j) = other.r;
        G.col(j) = s.B * other.r;  // consistent with this B
      }
      expectColumnsAsSolves(partition, R, G);
      Eigen::MatrixXd none_dx, none_dmu;  // no right-hand side: empty blocks of the right heights
      partition.solveColumns(Eigen::MatrixXd(c.n, 0), Eigen::MatrixXd(c.m, 0), none_dx, &none_dmu);
      EXPECT_EQ(none_dx.rows(), c.n);
      EXPECT_EQ(none_dx.cols(), 0);
      EXPECT_EQ(none_dmu.rows(), c.m);
    }
}

// A partition copied from another (copyConstraintFactors, as the exact gradients' sweeps take the one
// each time point computed) solves as the one that factored B itself, to the bit: the same factors.
// Its transposed pseudo-inverse is the minimum-norm least-squares solution of Bᵀμ = w, which the
// normal equations of B's rows characterise independently: μ lies in the range of B (μ = B z) and
// B(Bᵀμ − w) = 0. With a dependent row the solution is not unique and any other solution is longer.
TEST(SvdPartition, CopiedFactorsSolveAsTheirOriginAndTheTransposedPseudoInverseIsMinimumNorm) {
  for (const bool dependent : {false, true})
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const System s = randomSystem(7, 4, dependent, seed);
      SvdPartition original(1e-8), copy(0.5);  // the copy's own threshold must not matter
      original.setConstraintJacobian(s.B);
      copy.setConstraintJacobian(randomSystem(5, 2, false, seed + 50).B);  // other sizes before
      copy.copyConstraintFactors(original);
      ASSERT_EQ(copy.rank(), dependent ? 3 : 4);
      ASSERT_TRUE(original.setIterationMatrix(s.J));
      ASSERT_TRUE(copy.setIterationMatrix(s.J));
      Eigen::VectorXd dx, dmu, copy_dx, copy_dmu;
      original.solve(s.r, s.g, dx, dmu);
      copy.solve(s.r, s.g, copy_dx, copy_dmu);
      EXPECT_TRUE(dx == copy_dx);
      EXPECT_TRUE(dmu == copy_dmu);

      const Eigen::VectorXd w = randomSystem(7, 1, false, seed + 90).r;
      Eigen::VectorXd mu;
      copy.transposedPseudoInverse(w, mu);
      const double scale = s.B.norm() * s.B.norm() * w.norm();
      EXPECT_LT((s.B * (s.B.transpose() * mu - w)).norm(), 1e-13 * scale);  // least squares
      // In the range of B: its component along B's null space (left singular vectors of B's zero
      // singular values) vanishes.
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.B, Eigen::ComputeFullU);
      const Eigen::Index rank = copy.rank();
      EXPECT_LT((svd.matrixU().rightCols(4 - rank).transpose() * mu).norm(), 1e-13 * mu.norm() + 1e-300);
      if (dependent) {  // another solution, along the dependence 0.5 r₀ − 2 r₁ − r₃ = 0, is longer
        Eigen::VectorXd other = mu;
        other += 0.1 * Eigen::Vector4d(0.5, -2.0, 0.0, -1.0);
        EXPECT_LT((s.B.transpose() * (other - mu)).norm(), 1e-14 * scale);
        EXPECT_GT(other.norm(), mu.norm());
      }
    }
}

// J = M given by its articulated-body factorization: the range-space solves, on the closed chains
// (3 closure rows of rank 2) at their starting geometry. Their residuals in the augmented system
// vanish to round-off as the partition's do, and they agree with the partition's solution from the
// CRBA M to within what two backward-stable solutions of one system may differ by, κ(M)·ε times a
// margin of 100.
TEST(SvdPartition, RangeSpaceSolveWithTheArticulatedMassEqualsThePartitions) {
  for (const int links : {6, 24, 64}) {
    const Scene scene = closedPlanarChainScene(links);
    const Model& model = scene.model;
    Workspace<double> ws(model);
    Eigen::VectorXd b;
    Eigen::MatrixXd B, M;
    constraintJacobian(model, ws, scene.q0, b, B);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.coordinateCount());
    forwardKinematics(model, ws, scene.q0, zero, zero, KinematicsLevel::Velocity);
    massMatrix(model, ws, M);
    ArticulatedBodyFactorization articulated;
    ASSERT_TRUE(articulated.factor(model, ws, allCoordinates(model)));
    SvdPartition dense(1e-8), range(1e-8);
    dense.setConstraintJacobian(B);
    range.setConstraintJacobian(B);
    ASSERT_EQ(range.rank(), 2);
    ASSERT_TRUE(dense.setIterationMatrix(M));
    ASSERT_TRUE(range.setIterationMatrix(articulated));
    const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    const double tolerance = 100.0 * eigenvalues.maxCoeff() / eigenvalues.minCoeff() * std::numeric_limits<double>::epsilon();
    std::mt19937 generator(static_cast<unsigned>(links));
    std::uniform_real_distribution<double> entry(-1.0, 1.0);
    const auto random = [&](Eigen::Index n) { return Eigen::VectorXd::NullaryExpr(n, [&] { return entry(generator); }).eval(); };
    const Eigen::VectorXd r = random(M.rows()), g = B * random(M.rows());
    Eigen::VectorXd dx, dmu, dx_dense, dmu_dense;
    range.solve(r, g, dx, dmu);
    dense.solve(r, g, dx_dense, dmu_dense);
    const double scale = M.norm() * dx.norm() + B.norm() * dmu.norm() + r.norm();
    EXPECT_LT((M * dx + B.transpose() * dmu + r).norm(), 1e-12 * scale) << links << " links";
    EXPECT_LT((B * dx + g).norm(), 1e-12 * (B.norm() * dx.norm() + g.norm())) << links << " links";
    EXPECT_LT((dx - dx_dense).norm(), tolerance * dx_dense.norm()) << links << " links, κ(M) ε ×100 = " << tolerance;
    EXPECT_LT((dmu - dmu_dense).norm(), tolerance * dmu_dense.norm()) << links << " links";
    Eigen::VectorXd projection, projection_dense;
    range.project(g, projection);
    dense.project(g, projection_dense);
    EXPECT_LT((projection - projection_dense).norm(), tolerance * projection_dense.norm()) << links << " links";
    Eigen::MatrixXd R(M.rows(), 3), G(B.rows(), 3);
    for (Eigen::Index j = 0; j < 3; ++j) {
      R.col(j) = random(M.rows());
      G.col(j) = B * random(M.rows());
    }
    expectColumnsAsSolves(range, R, G);
    expectColumnsAsSolves(dense, R, G);
  }
}

// C = A B, C += A B, C −= A B and Aᵀ B against Eigen's products, for every row count of the unrolled
// kernels (1-8) and beyond (the loop), with empty inner dimensions and no columns; C = A B into a
// matrix of another size (resized). Each coefficient sums c₀ (when updated) and `inner` products in
// some order: both results are within γ_{inner+1}(|c₀| + Σ|aᵢₖ||bₖⱼ|) of the exact value, γₙ = nε/(1 − nε)
// (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1), so they differ by at most
// 2(inner + 2)ε(|c₀| + Σ|aᵢₖ||bₖⱼ|) for inner ≤ 11.
TEST(SmallProducts, EqualEigensProductsToRoundoff) {
  std::mt19937 generator(11);
  using test_support::kEpsilon;
  using test_support::randomMatrix;
  for (Eigen::Index rows : {1, 2, 3, 4, 5, 6, 7, 8, 9, 13})
    for (Eigen::Index inner : {0, 1, 3, 5, 11})
      for (Eigen::Index cols : {0, 1, 4}) {
        const Eigen::MatrixXd a = randomMatrix(rows, inner, generator), b = randomMatrix(inner, cols, generator);
        const Eigen::MatrixXd c0 = randomMatrix(rows, cols, generator);
        const Eigen::MatrixXd products = a.cwiseAbs() * b.cwiseAbs();
        const double factor = 2.0 * static_cast<double>(inner + 2) * kEpsilon;
        const auto expectNear = [&](const Eigen::MatrixXd& got, const Eigen::MatrixXd& want, bool updated,
                                    const char* what) {
          ASSERT_EQ(got.rows(), want.rows()) << what;
          ASSERT_EQ(got.cols(), want.cols()) << what;
          const Eigen::MatrixXd bound = factor * (updated ? Eigen::MatrixXd(products + c0.cwiseAbs()) : products);
          EXPECT_TRUE(((got - want).cwiseAbs().array() <= bound.array()).all())
              << what << " rows " << rows << " inner " << inner << " cols " << cols;
        };
        Eigen::MatrixXd c(rows + 1, cols + 2);  // another size: C = A B resizes it
        multiply(a, b, c);
        expectNear(c, a * b, false, "C = A B");
        c = c0;
        multiply(a, b, c, Accumulate::Add);
        expectNear(c, c0 + a * b, true, "C += A B");
        c = c0;
        multiply(a, b, c, Accumulate::Subtract);
        expectNear(c, c0 - a * b, true, "C -= A B");
        const Eigen::MatrixXd at = a.transpose();  // inner × rows
        Eigen::MatrixXd ct(rows, cols);
        multiplyTransposed(at.data(), b.data(), ct.data(), rows, inner, cols);
        expectNear(ct, at.transpose() * b, false, "C = A' B");
      }
}

// Without constraints the partition is J itself.
TEST(SvdPartition, WithoutConstraintsSolvesJ) {
  const System s = randomSystem(30, 0, false, 7);
  SvdPartition partition(1e-8);
  partition.setConstraintJacobian(s.B);
  ASSERT_TRUE(partition.setIterationMatrix(s.J));
  Eigen::VectorXd dx, dmu;
  partition.solve(s.r, Eigen::VectorXd(0), dx, dmu);
  EXPECT_LT((s.J * dx + s.r).norm(), 1e-12 * (s.J.norm() * dx.norm() + s.r.norm()));
  EXPECT_EQ(dmu.size(), 0);
}

// Loop equations on a model whose coordinates are all driven: B has rows and no column. Nothing is
// free, so nothing is solved, and no singular value may be read.
TEST(SvdPartition, WithoutFreeCoordinatesHasNothingToSolve) {
  SvdPartition partition(1e-8);
  partition.setConstraintJacobian(Eigen::MatrixXd(2, 0));
  EXPECT_EQ(partition.rank(), 0);
  EXPECT_EQ(partition.singularValues().size(), 0);
  EXPECT_EQ(partition.freeDirections().size(), 0);
  EXPECT_TRUE(partition.setIterationMatrix(Eigen::MatrixXd(0, 0)));
  Eigen::VectorXd dx, dmu;
  partition.solve(Eigen::VectorXd(0), Eigen::VectorXd::Zero(2), dx, dmu);
  EXPECT_EQ(dx.size(), 0);
  EXPECT_TRUE(dmu.isZero(0.0));
}

}  // namespace
}  // namespace mbsopt
