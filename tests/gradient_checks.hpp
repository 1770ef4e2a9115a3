// Checks of design gradients shared by the gradient and problem-suite tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"

namespace mbsopt::test {

/// max |a − b| relative to the largest entry of b.
inline double relativeGap(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

/// The discrete adjoint against the direct method at x (two derivations of the same recursion): equal to
/// 1e-12 of the largest entry, which must not vanish (a check of zeros would pass anyway). Returns the adjoint's.
inline DesignGradient expectAdjointEqualsDirect(const DesignProblem& problem,
                                                const std::vector<ConstraintFunctional>& functionals,
                                                const Eigen::VectorXd& x) {
  DesignGradient adjoint = designGradient("adjoint", problem, functionals, x);
  const DesignGradient direct = designGradient("direct", problem, functionals, x);
  EXPECT_GT(direct.constraints.cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_LE(relativeGap(adjoint.constraints, direct.constraints), 1e-12);
  return adjoint;
}

/// Each row of `exact` (the constraints' gradients at x) against central differences at the best
/// step of a sweep, to `tolerance` of the row's largest entry: the differences' error is O(δ²)
/// truncation at large steps and the simulation's Newton tolerance over δ at small ones, so the
/// best step of 1e-3 … 1e-6 bounds it by both.
inline void expectCentralDifferencesAtTheBestStep(const DesignProblem& problem,
                                                  const std::vector<ConstraintFunctional>& functionals,
                                                  const Eigen::VectorXd& x, const DesignGradient& exact,
                                                  double tolerance) {
  std::vector<DesignGradient> sweep;
  for (const double step : {1e-3, 1e-4, 1e-5, 1e-6}) sweep.push_back(finiteDifferenceGradient(problem, functionals, x, step, true));
  // Over the design variables' columns: b_{k+1}'s is exact in every method and, often a row's largest
  // entry, would loosen the tolerance of the others (as `mbsopt gradcheck` measures).
  const Eigen::Index design = static_cast<Eigen::Index>(problem.design.variables.size());
  for (Eigen::Index r = 0; r < exact.constraints.rows(); ++r) {
    const Eigen::VectorXd row = exact.constraints.row(r).head(design).transpose();
    double best = std::numeric_limits<double>::infinity();
    for (const DesignGradient& fd : sweep)
      best = std::min(best, (fd.constraints.row(r).head(design).transpose() - row).cwiseAbs().maxCoeff());
    EXPECT_LE(best, tolerance * std::max(row.cwiseAbs().maxCoeff(), 1e-300)) << functionals[static_cast<std::size_t>(r)].name;
  }
}

}  // namespace mbsopt::test
