// An independent check of what an optimizer calls converged: the first-order (KKT) conditions at
// its point. NLopt's tests are on the step and the change in f; they are met just as well where an
// algorithm cannot move, e.g. MMA at a constraint that is active with a zero gradient, which is how
// the paper's ∫⟨φ⟩dt ≤ 0 looks everywhere on its feasible set.
#pragma once

#include "mbsopt/optimizers/nlp_problem.hpp"

namespace mbsopt {

/// min ‖D(∇f + Σ λᵢ ∇cᵢ)‖∞ / ‖D∇f‖∞ over the multipliers of the active constraints (inequalities within
/// `active_tolerance` of zero and bounds within that fraction of the range, λ ≥ 0; equalities, λ free), by an active-set
/// least-squares loop. 0 at a KKT point; 1 where no active constraint can balance ∇f at all. `at`
/// must hold the gradients at x. D holds each variable's range (upper − lower, or max(1, |x_j|)
/// where unbounded), so the residual does not depend on the units of the variables.
double firstOrderResidual(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& at,
                          double active_tolerance);

}  // namespace mbsopt
