// An independent check of what an optimizer calls converged: the first-order (KKT) conditions at
// its point, and the multipliers that satisfy them best. NLopt's tests are on the step and the
// change in f; they are met just as well where an algorithm cannot move, e.g. MMA at a constraint
// that is active with a zero gradient, which is how the paper's ∫⟨φ⟩dt ≤ 0 looks everywhere on its
// feasible set.
#pragma once

#include "mbsopt/optimizers/nlp_problem.hpp"

namespace mbsopt {

/// The multipliers of the Lagrangian L = f + Σ λᵢ cᵢ + Σ μᵤⱼ (xⱼ − uⱼ) + Σ μₗⱼ (lⱼ − xⱼ) that balance
/// ∇f best at a point (the paper's (7)-(8)). By the envelope theorem they are what relaxing each
/// constraint is worth at an optimum: the optimal f falls by λᵢ δ when cᵢ ≤ 0 becomes cᵢ ≤ δ, by
/// μᵤⱼ δ when uⱼ rises by δ, by μₗⱼ δ when lⱼ falls by δ.
struct FirstOrderMultipliers {
  Eigen::VectorXd constraints;  ///< λ, ≥ 0 for an inequality, free for an equality; 0 where inactive
  Eigen::VectorXd lower, upper; ///< μₗ, μᵤ ≥ 0; 0 where the bound is inactive
};

struct FirstOrderCheck {
  /// min ‖D(∇f + Σ λᵢ ∇cᵢ + bound terms)‖∞ / ‖D∇f‖∞: 0 at a KKT point, 1 where no active constraint
  /// can balance ∇f at all.
  double residual = 1.0;
  FirstOrderMultipliers multipliers;
};

/// The least-squares multipliers of the active constraints (inequalities within `active_tolerance` of
/// zero and bounds within that fraction of the range, λ ≥ 0; equalities, λ free), by an active-set
/// loop, and the residual they leave. `at` must hold the gradients at x. D holds each variable's range
/// (upper − lower, or max(1, |x_j|) where unbounded), so the residual does not depend on the units of
/// the variables.
FirstOrderCheck firstOrderCheck(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& at,
                                double active_tolerance);

}  // namespace mbsopt
