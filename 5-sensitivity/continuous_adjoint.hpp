// The `continuous-adjoint` gradient method: the paper's adjoint variable method (49)-(65),
// optimise-then-discretise. The adjoint equations are derived from the continuous equations of
// motion, then integrated backward on the simulation's grid with the trapezoidal rule; the
// gradient therefore differs from the discrete adjoint's (the exact derivative of the computed
// functional) by a discretisation error that vanishes as the step shrinks (5-sensitivity/README.md,
// "The continuous adjoint").
#pragma once

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// Gradients of the cost and of every transcribed constraint with respect to the scaled point x.
/// Throws std::invalid_argument for loops closed at acceleration level, and where the rank of the
/// closure changes within a step (a singular configuration), where the method does not apply.
/// `simulated`: the simulation at x when the caller has it (evaluateDesign's), so none is run again.
DesignGradient continuousAdjointGradient(const DesignProblem& problem,
                                         const std::vector<ConstraintFunctional>& functionals,
                                         const Eigen::VectorXd& x, const DesignResponse* simulated = nullptr);

}  // namespace mbsopt
