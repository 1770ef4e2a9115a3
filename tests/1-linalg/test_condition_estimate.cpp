// The O(n²) reciprocal-condition estimate (1-linalg/condition_estimate.hpp) against the exact
// 1-norm condition number computed independently from the explicit inverse: never below it (the
// estimate of ‖A⁻¹‖₁ is ‖A⁻¹x‖₁ for a unit x, a lower bound), and close to it; and the cheap lower
// bound that lets a step skip the estimate, never above it.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "mbsopt/linalg/condition_estimate.hpp"
#include "mbsopt/linalg/lu_factors.hpp"

namespace mbsopt {
namespace {

double exactReciprocalCondition(const Eigen::MatrixXd& a) {
  const auto oneNorm = [](const Eigen::MatrixXd& m) { return m.cwiseAbs().colwise().sum().maxCoeff(); };
  return 1.0 / (oneNorm(a) * oneNorm(a.inverse()));
}

double estimated(const Eigen::MatrixXd& a) {
  LuFactors lu;
  lu.compute(a);
  ConditionEstimator estimator;
  return estimator.reciprocalCondition(a, lu);
}

Eigen::MatrixXd hilbert(int n) {
  Eigen::MatrixXd h(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) h(i, j) = 1.0 / (i + j + 1);
  return h;
}

// The factors of lu_factors.hpp against their definition, P A = L U with the permutation a
// rearrangement of the rows, |l_ij| ≤ 1 (partial pivoting), to round-off of ‖A‖ times the growth
// factor (modest for random matrices); and a matrix with an exact zero pivot factors without a
// division by zero: its U has the zero on the diagonal.
TEST(LuFactors, FactorWithPartialPivoting) {
  std::mt19937 random(10);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  LuFactors lu;  // one object for every size: its buffers are resized
  for (int n = 1; n <= 40; ++n) {
    const Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return uniform(random); });
    lu.compute(a);
    const Eigen::MatrixXd l = lu.matrixLU().triangularView<Eigen::UnitLower>();
    const Eigen::MatrixXd u = lu.matrixLU().triangularView<Eigen::Upper>();
    Eigen::MatrixXd permuted(n, n);
    std::vector<int> seen(static_cast<std::size_t>(n), 0);
    for (int k = 0; k < n; ++k) {
      const int row = lu.rows()[static_cast<std::size_t>(k)];
      ASSERT_TRUE(row >= 0 && row < n);
      ++seen[static_cast<std::size_t>(row)];
      permuted.row(k) = a.row(row);
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), n) << "n = " << n;
    EXPECT_LE(l.cwiseAbs().maxCoeff(), 1.0);
    EXPECT_LE((permuted - l * u).cwiseAbs().maxCoeff(), 1e2 * n * std::numeric_limits<double>::epsilon() * u.cwiseAbs().maxCoeff())
        << "n = " << n;
  }
  Eigen::MatrixXd singular(3, 3);
  singular << 1, 2, 3, 2, 4, 6, 1, 1, 1;  // row 1 = 2 row 0, exactly: the last pivot is an exact zero
  lu.compute(singular);
  EXPECT_TRUE(lu.matrixLU().allFinite());
  EXPECT_EQ(lu.matrixLU().diagonal().cwiseAbs().minCoeff(), 0.0);
}

// The substitution loops of lu_factors.hpp against a residual computed independently: A x − b and
// Aᵀ x − b at round-off (‖A‖ ‖x‖ ε times a modest growth factor), for random matrices whose partial
// pivoting swaps rows, sizes 1 to 40.
TEST(LuSolve, SolvesWithTheMatrixAndItsTransposeToRoundOff) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int n = 1; n <= 40; ++n) {
    Eigen::MatrixXd a(n, n);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) {
      b[i] = uniform(random);
      for (int j = 0; j < n; ++j) a(i, j) = uniform(random);
    }
    LuFactors lu;
    lu.compute(a);
    Eigen::VectorXd x, w;
    const auto tolerance = [&](const Eigen::VectorXd& solution) {
      return 1e3 * n * std::numeric_limits<double>::epsilon() * a.cwiseAbs().colwise().sum().maxCoeff() *
             solution.cwiseAbs().sum();
    };
    luSolve(lu, b, x);
    EXPECT_LE((a * x - b).cwiseAbs().maxCoeff(), tolerance(x)) << "n = " << n;
    luSolveTransposed(lu, b, w, x);
    EXPECT_LE((a.transpose() * x - b).cwiseAbs().maxCoeff(), tolerance(x)) << "n = " << n;
  }
}

// Random matrices of every size to 40, well and badly scaled (rows scaled over 6 decades): the
// estimate is an upper bound of the exact reciprocal condition (to round-off of the solves, 1e-10
// relative). It has no guaranteed upper bound; Higham's experiments (ACM TOMS 14, 1988) found it
// frequently exact and rarely more than a factor 3 off, and so here: at least 9 in 10 within 3,
// every one within 10 (one decade, against the integrator's singularity threshold of 1e-13).
TEST(ConditionEstimate, BoundsTheExactConditionFromAboveAndIsRarelyMoreThanThreeOff) {
  std::mt19937 generator(20261124);
  std::uniform_real_distribution<double> entry(-1.0, 1.0), decade(-3.0, 3.0);
  int matrices = 0, within_three = 0;
  for (int n = 1; n <= 40; ++n)
    for (int trial = 0; trial < 10; ++trial) {
      Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return entry(generator); });
      if (trial % 2 == 1)
        for (int i = 0; i < n; ++i) a.row(i) *= std::pow(10.0, decade(generator));
      const double exact = exactReciprocalCondition(a), estimate = estimated(a);
      EXPECT_GE(estimate, exact * (1.0 - 1e-10)) << "n = " << n << ", trial " << trial;
      EXPECT_LE(estimate, 10.0 * exact) << "n = " << n << ", trial " << trial;
      within_three += estimate <= 3.0 * exact;
      ++matrices;
    }
  EXPECT_EQ(matrices, 400);
  EXPECT_GE(within_three, 360);
}

// Hilbert matrices: condition numbers from 1e1 (n = 2) to 1e13 (n = 10), the range where the
// integrator's singularity test (1e-13) decides.
TEST(ConditionEstimate, TracksTheIllConditionedHilbertMatrices) {
  for (int n = 2; n <= 10; ++n) {
    const Eigen::MatrixXd h = hilbert(n);
    const double exact = exactReciprocalCondition(h), estimate = estimated(h);
    EXPECT_GE(estimate, exact * (1.0 - 1e-6)) << n;  // the inverse itself is off by κε ≈ 1e-4 at n = 10
    EXPECT_LE(estimate, 3.0 * exact) << n;
  }
}

// A singular matrix (two equal rows) is reported singular: 0 when U has an exact zero pivot, and
// below the integrator's 1e-13 when round-off leaves a tiny one.
TEST(ConditionEstimate, ReportsSingularMatrices) {
  Eigen::MatrixXd exact_zero_pivot(3, 3);
  exact_zero_pivot << 1, 2, 3, 1, 2, 3, 4, 5, 6;
  EXPECT_EQ(estimated(exact_zero_pivot), 0.0);
  Eigen::MatrixXd a = hilbert(6);
  a.row(5) = a.row(2) * (1.0 / 3.0) + a.row(4) * (2.0 / 3.0);  // dependent up to round-off
  EXPECT_LT(estimated(a), 1e-13);
  EXPECT_EQ(estimated(Eigen::MatrixXd(0, 0)), 1.0);
}

double lowerBound(const Eigen::MatrixXd& a) {
  LuFactors lu;
  lu.compute(a);
  Eigen::VectorXd scratch;
  return reciprocalConditionLowerBound(a, lu, scratch);
}

// The cheap bound the integrator tries first is a lower bound of the exact reciprocal condition
// (‖A⁻¹‖₁ ≤ ‖U⁻¹‖₁‖L⁻¹‖₁ ≤ the comparison matrices' norms), on the same random matrices and on
// Hilbert's; so "bound above the threshold" implies "estimate above the threshold" (the estimate is
// never below the exact value). Diagonal matrices have no off-diagonal terms to overestimate, and
// their bound is their exact reciprocal condition min|dᵢ| / max|dᵢ|.
TEST(ConditionLowerBound, NeverExceedsTheExactReciprocalConditionAndIsExactForDiagonalMatrices) {
  std::mt19937 generator(20261125);
  std::uniform_real_distribution<double> entry(-1.0, 1.0), decade(-3.0, 3.0);
  for (int n = 1; n <= 40; ++n)
    for (int trial = 0; trial < 10; ++trial) {
      Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return entry(generator); });
      if (trial % 2 == 1)
        for (int i = 0; i < n; ++i) a.row(i) *= std::pow(10.0, decade(generator));
      const double bound = lowerBound(a);
      EXPECT_GT(bound, 0.0) << "n = " << n << ", trial " << trial;
      EXPECT_LE(bound, exactReciprocalCondition(a) * (1.0 + 1e-10)) << "n = " << n << ", trial " << trial;
      Eigen::VectorXd d = Eigen::VectorXd::NullaryExpr(n, [&] { return entry(generator) * std::pow(10.0, decade(generator)); });
      const double exact = d.cwiseAbs().minCoeff() / d.cwiseAbs().maxCoeff();
      EXPECT_NEAR(lowerBound(d.asDiagonal().toDenseMatrix()), exact, 1e-15 * exact) << "n = " << n;
    }
  for (int n = 2; n <= 10; ++n) {
    const Eigen::MatrixXd h = hilbert(n);
    EXPECT_LE(lowerBound(h), exactReciprocalCondition(h) * (1.0 + 1e-6)) << n;
  }
  Eigen::MatrixXd exact_zero_pivot(3, 3);
  exact_zero_pivot << 1, 2, 3, 1, 2, 3, 4, 5, 6;
  EXPECT_EQ(lowerBound(exact_zero_pivot), 0.0);
  EXPECT_EQ(lowerBound(Eigen::MatrixXd(0, 0)), 1.0);
}

}  // namespace
}  // namespace mbsopt
