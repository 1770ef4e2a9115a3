// The `direct` gradient method (docs/design.md §4): forward sensitivities S = d(q, q̇, q̈)/db carried
// through every Newmark step (32)-(33), one extra right-hand side per design variable per step,
// then chained with the time functionals' sample gradients and the response Jacobians. The exact
// derivative of the discrete map (steps 1-3 of "The discrete map" in 5-sensitivity/README.md), closed
// loops included (the cut joints' multipliers through the augmented solve, augmented_solve.hpp).
#pragma once

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// Gradients of the cost and of every transcribed constraint with respect to the scaled point x.
/// Throws std::invalid_argument for loops closed at acceleration level.
/// `simulated`: the simulation at x when the caller has it (evaluateDesign's), so none is run again.
/// `jobs`: threads for the step derivatives, which do not depend on the recursion (the recursion
/// itself is sequential); without `simulated` and with jobs ≥ 2 they start during the simulation,
/// each as soon as its step is done (TrajectoryDerivatives). The gradient is the same to the bit
/// whatever the number.
DesignGradient directGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x, const DesignResponse* simulated = nullptr, int jobs = 1);

}  // namespace mbsopt
