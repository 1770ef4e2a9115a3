// The discretisation error of a design problem's cost and constraints at one point
// (`mbsopt optimize --accuracy`; docs/integrators.md §8): the problem's values on its grid h and on
// h/2 and h/4, the error of the values at h from their differences and the order they show.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// The cost's functional (costFunctional, SI) and the transcribed constraints of a problem at a point.
struct GridValues {
  double cost = 0.0;
  Eigen::VectorXd constraints;
};

/// The values of `problem` (one Newmark run per scene, on its step or its time grid) at the scaled point x.
GridValues gridValues(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                      const Eigen::VectorXd& x);

struct DiscretisationError {
  double step = 0.0;        ///< h [s]: the fixed step, or a variable step sequence's largest step
  bool variable_steps = false;  ///< the grid is a variable step sequence (an adaptive run's, NewmarkSettings::time_grid)
  /// Where the grid crosses a jump of the accelerations in one short step (gradedTimeGrid); empty
  /// for a uniform grid and a variable step sequence.
  std::vector<double> break_times;
  double cost = 0.0;        ///< the cost's functional at h (costFunctional, SI)
  double cost_error = 0.0;  ///< its estimated error |ψ_h − ψ|
  /// Each transcribed constraint's, in its own units, with the order its own values show (value at h
  /// minus the converged value, as every estimate of docs/integrators.md).
  Eigen::VectorXd constraint_errors;
  Eigen::VectorXd constraint_values;  ///< the transcribed constraints at h (≤ 0: satisfied)
  /// The order the cost's values show, log₂ |ψ_h − ψ_{h/2}| / |ψ_{h/2} − ψ_{h/4}|, clamped to [1, 4]
  /// (a functional of extremes or of ⟨·⟩ converges irregularly: the clamp keeps the estimate
  /// conservative).
  double order = 0.0;
  /// Whether constraint j can be active on a finer grid: its value is not below zero by more than
  /// twice its estimated error (the estimates hold within a factor of 2, docs/integrators.md §8). One
  /// satisfied by more cannot bind the optimum, however its value's error moves it.
  bool canBeActive(Eigen::Index j) const;
  /// The largest of cost_error and |constraint_errors| of the constraints that can be active: the
  /// errors that move the optimum.
  double largest() const;
  /// The largest |constraint_errors| of the constraints that can be active, and of all of them.
  double largestActiveConstraintError() const;
  double largestConstraintError() const;
};

/// The errors of the values on h (values[0]) from those on h/2 and h/4 (values[1], values[2]):
/// e_h = (ψ_h − ψ_{h/2}) / (1 − 2^{−p}) with p the order each value shows. The grid's description
/// (step, variable_steps, break_times) is the caller's to fill in.
DiscretisationError discretisationError(const std::array<GridValues, 3>& values);

}  // namespace mbsopt
