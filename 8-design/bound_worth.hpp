// What relaxing each active bound of a design problem is worth at its optimum, in the problem's own
// units (the paper's §2.1, (7)-(8): dΨ₀/de_i = −v_i, the sensitivity of the optimal cost to a
// constraint's right-hand side is its multiplier). The multipliers are the optimizer's problem's
// (first_order_check.hpp: of the transcribed constraints g_j ≤ 0 and the scaled variables' bounds);
// by the envelope theorem the optimal f = b_{k+1} moves with a constraint's bound B as
// Σ_j λ_j ∂g_j/∂B (boundJacobian: exact, whatever the formulation), and with a variable's bound as
// its multiplier over its scale. At a converged optimum b_{k+1} is the cost's own functional (to the
// feasibility tolerance), so these are the derivatives of the optimal cost.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/optimizers/first_order_check.hpp"

namespace mbsopt {

struct BoundWorth {
  enum class Kind { Constraint, LowerBound, UpperBound };
  Kind kind = Kind::Constraint;
  /// The constraint's report name (yaw_front_max_abs; one bound for every load case), or the design
  /// variable's parameter (front_secondary.k).
  std::string name;
  /// Its place in DesignDescription::constraints or DesignDescription::variables: the dotted name
  /// design.constraints.INDEX.bound, or design.variables.INDEX.lower / .upper, moves it.
  int index = 0;
  std::string unit;  ///< the bound's: the constraint's reported unit (deg for an angle), a parameter's (parameterUnit; "" where it has none)
  double bound = 0.0;  ///< in `unit`
  bool equality = false;
  /// Whether raising the bound relaxes it (a maximum's, an integral's, a final value's, an RMS's bound,
  /// an upper bound), not lowering it (a minimum's bound, a lower bound). Meaningless for an equality.
  bool raising_relaxes = true;
  /// d(optimal cost)/d(bound): the change of the optimal cost (in the cost's reported unit) as the
  /// bound rises by one `unit`. Raising a maximum's bound or an upper bound relaxes it (derivative ≤ 0),
  /// lowering a minimum's bound or a lower bound does (≥ 0).
  double derivative = 0.0;
  /// The reports' tolerance of a constraint, in `unit` (constraintTolerance); 0 for a variable's bound.
  double tolerance = 0.0;
  /// How much relaxing the bound by one `unit` lowers the optimal cost (≥ 0 at a KKT point):
  /// |derivative| in the direction that relaxes it; for an equality, the derivative itself.
  double relaxingLowersCostBy() const;
};

/// The bounds with a nonzero multiplier at a point of `problem` (as the optimizer saw it: its
/// transcription), from the optimizer's multipliers there, the functionals and the response at that
/// point. The constraints first, in their order, then the design variables' bounds.
std::vector<BoundWorth> boundWorth(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                   const DesignResponse& response, const FirstOrderMultipliers& multipliers);

/// What the constraints' tolerances are worth: Σ |derivative| × tolerance, in the cost's reported
/// unit. A feasible point may lie below the optimal cost by up to about this much, by using them.
double toleranceWorth(const std::vector<BoundWorth>& worth);

}  // namespace mbsopt
