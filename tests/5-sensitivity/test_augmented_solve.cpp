// The augmented systems of the exact gradient methods (5-sensitivity/augmented_solve.hpp): the solve
// [J Bᵀ; B 0][X; Y] = [top; bottom] through B's SVD partition, with Y the minimum-norm multipliers,
// and its transpose, which the adjoint sweeps use. The transpose is checked by its defining identity
// x̄ X + ȳ Y = t̄ top + b̄ bottom for arbitrary right-hand sides, on a B with redundant rows (the
// partition drops them; Y then has no part along null(Bᵀ)).
#include <gtest/gtest.h>

#include <random>

#include "mbsopt/sensitivity/augmented_solve.hpp"
#include "tests/random_matrices.hpp"

namespace mbsopt {
namespace {

using test_support::randomMatrix;

struct System {
  Eigen::MatrixXd J, B, top, bottom;
};

/// n = 7 coordinates, m = 4 closure rows of rank 3 (the last row the sum of the first two), a
/// non-symmetric J made regular on B's null space by a dominant diagonal; p = 3 right-hand sides,
/// the bottom ones in B's range (consistent, as a closure's are).
System redundantSystem(std::mt19937& generator) {
  System s;
  s.J = randomMatrix(7, 7, generator) + 6.0 * Eigen::MatrixXd::Identity(7, 7);
  s.B = randomMatrix(4, 7, generator);
  s.B.row(3) = s.B.row(0) + s.B.row(1);
  s.top = randomMatrix(7, 3, generator);
  s.bottom = s.B * randomMatrix(7, 3, generator);
  return s;
}

constexpr double kThreshold = 1e-8;

/// X and Y of the system's forward solve.
struct Solution {
  Eigen::MatrixXd X, Y;
};
Solution solveForward(const System& s) {
  AugmentedSolver solver(s.B, kThreshold);
  solver.setMatrix(s.J);
  Solution out;
  solver.solve(s.top, s.bottom, out.X, out.Y);
  return out;
}

// Y solves the first row with the X of the solve and has no part along null(Bᵀ), so it is the
// unique minimum-norm multiplier: J X + Bᵀ Y = top and B X = bottom to round-off, and Y ⟂ (1, 1, 0, −1).
TEST(AugmentedSolve, TheMultipliersAreTheMinimumNormOnes) {
  std::mt19937 generator(11);
  const System s = redundantSystem(generator);
  const auto [X, Y] = solveForward(s);
  EXPECT_LE((s.J * X + s.B.transpose() * Y - s.top).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LE((s.B * X - s.bottom).cwiseAbs().maxCoeff(), 1e-13);
  const Eigen::Vector4d null_direction(1.0, 1.0, 0.0, -1.0);
  EXPECT_LE((null_direction.transpose() * Y).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(X, solveAugmented(s.J, s.B, s.top, s.bottom, kThreshold));  // the same X as without Y, to the bit
}

// The transposed solve with a seed on the multipliers: for two adjoint rows (x̄, ȳ), and any top and
// bottom (the bottom in B's range), x̄ X + ȳ Y = t̄ top + b̄ bottom. Without ȳ the same identity holds
// with x̄ alone, and the seeded solve with ȳ = 0 gives the same t̄ and b̄.
TEST(AugmentedSolve, TheTransposeCarriesASeedOnTheMultipliers) {
  std::mt19937 generator(12);
  const System s = redundantSystem(generator);
  const auto [X, Y] = solveForward(s);
  const Eigen::MatrixXd xbar = randomMatrix(2, 7, generator), ybar = randomMatrix(2, 4, generator);
  AugmentedSolver backward(s.B, kThreshold);
  backward.setTransposedMatrix(s.J);
  Eigen::MatrixXd tbar, bbar;
  backward.solveTransposed(xbar, ybar, tbar, bbar);
  const Eigen::MatrixXd lhs = xbar * X + ybar * Y, rhs = tbar * s.top + bbar * s.bottom;
  EXPECT_LE((lhs - rhs).cwiseAbs().maxCoeff(), 1e-13 * lhs.cwiseAbs().maxCoeff());
  Eigen::MatrixXd tbar_x, bbar_x, tbar_zero, bbar_zero;
  backward.solveTransposed(xbar, tbar_x, bbar_x);
  const Eigen::MatrixXd plain = xbar * X, plain_rhs = tbar_x * s.top + bbar_x * s.bottom;
  EXPECT_LE((plain - plain_rhs).cwiseAbs().maxCoeff(), 1e-13 * plain.cwiseAbs().maxCoeff());
  backward.solveTransposed(xbar, Eigen::MatrixXd::Zero(2, 4), tbar_zero, bbar_zero);
  EXPECT_LE((tbar_zero - tbar_x).cwiseAbs().maxCoeff(), 1e-15 * tbar_x.cwiseAbs().maxCoeff());
  EXPECT_LE((bbar_zero - bbar_x).cwiseAbs().maxCoeff(), 1e-15 * bbar_x.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace mbsopt
