// The discretisation error of a design problem's cost and constraints at one point (issue 18,
// `mbsopt optimize --accuracy`; docs/integrators.md §8): the problem evaluated on its grid h and on
// h/2 and h/4 (a variable step sequence, every step halved), the error of the values at h from their
// differences and the order they show.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

struct DiscretisationError {
  double step = 0.0;        ///< h [s]; of a variable step sequence, its largest step
  bool variable_steps = false;  ///< the grid is a variable step sequence (NewmarkSettings::time_grid)
  double cost = 0.0;        ///< the cost's functional at h (costFunctional, SI)
  double cost_error = 0.0;  ///< its estimated error |ψ_h − ψ|
  /// Each transcribed constraint's, in its own units, with the order its own values show (value at h
  /// minus the converged value, as every estimate of docs/integrators.md).
  Eigen::VectorXd constraint_errors;
  /// The order the cost's values show, log₂ |ψ_h − ψ_{h/2}| / |ψ_{h/2} − ψ_{h/4}|, clamped to [1, 4]
  /// (a functional of extremes or of ⟨·⟩ converges irregularly: the clamp keeps the estimate
  /// conservative).
  double order = 0.0;
  /// The largest of cost_error and |constraint_errors|.
  double largest() const;
};

/// The values of the problem (one Newmark run per grid, at its scene's step h or on its time grid) at the
/// scaled point x on h, h/2, h/4 (every grid ending where h's does; a time grid's steps halved), and
/// their error at h: e_h = (ψ_h − ψ_{h/2}) / (1 − 2^{−p})
/// with p the order each value shows.
DiscretisationError discretisationError(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                        const Eigen::VectorXd& x);

}  // namespace mbsopt
