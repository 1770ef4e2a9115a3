// The paper's optimizer (§2.2, (6)-(11)): steepest descent with constraint compensation (SDCC).
// At a design b, the ε-active constraints Ψ̃ (7) are linearized (8)-(9); the step is the
// W-projected steepest descent δb₁ plus the compensation δb₂ that moves Ψ̃ to zero, the two
// W-orthogonal and together bounded by δbᵀWδb ≤ ξ² (10); an inequality whose multiplier (11) is
// negative leaves the active set. What the paper leaves open, and what this implementation chose:
// - bounds (the paper's (14)) are inequality constraints, but one joins the active set only where
//   the step would cross it (as in a projected-gradient method on a box): taken as equalities of the
//   projection whenever within ε, they kept a variable on its bound where the compensation needed to
//   move it off; and a step is clipped to the bounds, so no point outside them is ever evaluated;
// - a trial step is accepted on an exact-penalty merit f + ρ·(max violation) when it achieves a
//   fraction of the decrease the linearization (8)-(9) predicts (the cost alone would refuse the
//   compensation steps that must raise it, and tangent steps along a curved constraint raise the
//   violation by O(ξ²)); ξ shrinks on a rejection and grows when the prediction was good;
// - where the compensation cannot zero every active constraint (more than the variables can meet),
//   the satisfied inequality with the most negative compensation multiplier leaves;
// - ρ grows so that a step which lowers the predicted violation also predicts a lower merit;
// - the run ends at a feasible KKT point, or when ξ falls below its floor (NLopt's xtol_rel):
//   converged if the point is feasible (where the active constraints' gradients vanish or jump at
//   the optimum, no KKT point can be certified), failed if not.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/optimizers/optimizer.hpp"

namespace mbsopt {

struct SdccSettings {
  /// ε of (7): an inequality Ψᵢ ≤ 0 is active when Ψᵢ ≥ −ε (equalities always are).
  double active_set_epsilon = 1e-2;
  /// The diagonal of W in (10), one positive entry per variable; empty means the identity.
  Eigen::VectorXd weights;
  /// ξ of (10) at the start, in the W-norm ‖δb‖_W = √(δbᵀWδb).
  double initial_step_bound = 0.1;
  /// ξ is multiplied by this after a rejected step (or a failed evaluation).
  double shrink_factor = 0.5;
  /// ξ is multiplied by this after an accepted step whose merit decrease was at least
  /// `growth_ratio` of the linear prediction (the linearization (8)-(9) held over the step).
  double growth_factor = 2.0;
  double growth_ratio = 0.75;
  /// A step is accepted when its merit decrease is at least this fraction of the predicted one.
  double acceptance_ratio = 0.1;
  /// The run ends when ξ falls below options.tolerance × max(1, ‖b‖_W) (NLopt's xtol_rel) or this:
  /// converged at a feasible point (no shorter step lowers the merit), failed at an infeasible one.
  double min_step_bound = 1e-10;
  /// Converged when ‖δb₁‖_W ≤ this × max(1, ‖W^{-1/2} l₀(b₀)‖) and the max violation is within the
  /// options' feasibility tolerance. Relative to the first gradient, so independent of f's units;
  /// not options.tolerance, which asks for more than a first-order method can see in f's round-off.
  double stationarity_tolerance = 1e-7;
  /// The merit's penalty ρ (cost units per unit of violation) starts here, never falls, and is kept
  /// at least `penalty_factor` × ‖μ₁‖₁ (an exact penalty needs ρ > ‖μ‖₁) and `penalty_factor` × the
  /// cost a step adds over the violation it removes (so that it predicts a decrease). It must start positive:
  /// where ∇f = 0 (μ₁ = 0) only the penalty credits a compensation step.
  double initial_penalty = 1.0;
  double penalty_factor = 2.0;
};

/// The defaults with the named settings applied (names as the fields above; `weights` a comma-separated
/// list); throws std::invalid_argument for an unknown name or a value that is not a number.
SdccSettings sdccSettings(const NamedSettings& named);

/// The constraints at one design in the paper's form, bounds included (14): the first
/// `equality_count` are Ψᵢ = 0, the rest Ψᵢ ≤ 0; their gradients are the columns of `gradients`.
struct ConstraintLinearization {
  Eigen::VectorXd values;
  Eigen::MatrixXd gradients;
  Eigen::Index equality_count = 0;
  /// The last bound_count constraints are the variables' bounds (x − upper ≤ 0, lower − x ≤ 0). A
  /// bound joins the active set only where the step would cross it (sdccStep).
  Eigen::Index bound_count = 0;
};

/// One SDCC step at a design: the active set after dropping the negative multipliers, and the parts
/// of the step δb = scale_descent·δb₁ + scale_compensation·δb₂.
struct SdccStep {
  std::vector<Eigen::Index> active;  ///< indices into the linearization's constraints
  Eigen::VectorXd multipliers;       ///< μ₁, one per active constraint
  Eigen::VectorXd descent;           ///< δb₁, the W-projected steepest descent
  Eigen::VectorXd compensation;      ///< δb₂, which zeroes the active constraints' linearization
  double scale_descent = 0.0;        ///< 1/(2γ) of (11); 0 when the compensation uses the whole ξ
  double scale_compensation = 0.0;   ///< 1, or ξ/‖δb₂‖_W when the compensation alone exceeds ξ
  Eigen::VectorXd step;              ///< δb, with ‖δb‖_W ≤ ξ
};

/// The step (7)-(11) from the cost gradient l₀ and the constraints, for the weights W (diagonal,
/// as a vector), the ε of (7) and the step bound ξ of (10).
SdccStep sdccStep(const Eigen::VectorXd& cost_gradient, const ConstraintLinearization& constraints,
                  const Eigen::VectorXd& weights, double epsilon, double step_bound);

/// Minimizes the problem with SDCC. `options.max_iterations` bounds the trial steps (each is one
/// evaluation with gradients), so the run evaluates at most max_iterations + 1 points.
OptimizerResult minimizeWithSdcc(NlpProblem& problem, const OptimizerOptions& options,
                                 const SdccSettings& settings = {});

}  // namespace mbsopt
