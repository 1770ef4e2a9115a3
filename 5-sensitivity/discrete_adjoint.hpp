// The `adjoint` gradient method (docs/design.md §4, the default): the discrete adjoint of the Newmark
// steps, i.e. the transpose of the `direct` recursion swept backward in time. One sweep serves every
// constraint (one adjoint row each) whatever the number of design variables, and gives the exact
// gradient of the discretised functionals, closed loops included.
#pragma once

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// Gradients of the cost and of every transcribed constraint with respect to the scaled point x.
/// Throws std::invalid_argument for loops closed at acceleration level.
/// `simulated`: the simulation at x when the caller has it (evaluateDesign's), so none is run again.
/// `jobs`: threads for the step derivatives, which do not depend on the sweep (the sweep itself is
/// sequential); without `simulated` and with jobs ≥ 2 they start during the simulation, each as
/// soon as its step is done (TrajectoryDerivatives). The gradient is the same to the bit whatever
/// the number.
DesignGradient adjointGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                               const Eigen::VectorXd& x, const DesignResponse* simulated = nullptr, int jobs = 1);

}  // namespace mbsopt
