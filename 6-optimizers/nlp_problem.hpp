// What every optimizer minimises (docs/design.md §5): a smooth nonlinear program
//   min f(x)  subject to  g(x) ≤ 0,  h(x) = 0,  lower ≤ x ≤ upper,
// evaluated as one call that returns the values and, on request, the gradients (for the design
// problems one call is one simulation, plus one gradient computation). The shape of Ipopt's TNLP
// and of NLopt's objective callbacks, without either.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>

namespace mbsopt {

/// f, [g; h] and, when requested, ∇f and the Jacobian of [g; h] (one row per constraint).
struct NlpEvaluation {
  double cost = 0.0;
  Eigen::VectorXd constraints;          ///< the inequalities g first, then the equalities h
  Eigen::VectorXd cost_gradient;        ///< empty unless gradients were requested
  Eigen::MatrixXd constraint_jacobian;  ///< empty unless gradients were requested
  /// The quantity the problem reports as its cost, where that is not f itself (a design problem: its
  /// cost sensor's functional, which the artificial variable f = b_{k+1} bounds); NaN: f.
  double reported_cost = std::numeric_limits<double>::quiet_NaN();
  /// How far the problem's own constraints lie beyond their bounds in their own units, where the
  /// problem judges them apart from the transcription g, h the optimizers see (a design problem: each
  /// constraint's value against its bound, whatever the formulation): the largest excess over its
  /// tolerance (≤ 1: every one met); NaN: the problem has no judgement of its own, and the
  /// transcription's violation decides (OptimizerOptions::feasibility_tolerance).
  double excess_over_tolerance = std::numeric_limits<double>::quiet_NaN();
};

class NlpProblem {
 public:
  virtual ~NlpProblem() = default;

  virtual Eigen::Index variableCount() const = 0;
  virtual Eigen::Index inequalityCount() const = 0;  ///< g(x) ≤ 0
  virtual Eigen::Index equalityCount() const { return 0; }  ///< h(x) = 0
  virtual Eigen::VectorXd lowerBounds() const = 0;
  virtual Eigen::VectorXd upperBounds() const = 0;
  virtual Eigen::VectorXd start() const = 0;
  /// A name for constraint i (0 ≤ i < inequalityCount() + equalityCount()), for reports.
  virtual std::string constraintName(Eigen::Index i) const {
    std::string name = "c";
    name += std::to_string(i);
    return name;
  }

  /// The values at x, and the gradients too when `gradients` is set. May throw; the optimizers
  /// turn an exception into a failed result that says why.
  virtual void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) = 0;

  /// A hint: the optimizer may ask next for the values at x (SDCC: the trial it would take should the
  /// one it is about to evaluate be rejected). A problem with a spare core may start evaluating them
  /// in the background, so that evaluate(x) then finds them ready. It never changes what evaluate()
  /// returns; the default ignores it.
  virtual void anticipate(const Eigen::VectorXd& /*x*/) {}

  /// What one gradient evaluation costs beyond the simulation of its values, in simulation-
  /// equivalents (one value evaluation = 1): the unit of OptimizerOptions::budget. Counted, not
  /// timed while a run goes on, so that a budget stops a run at the same evaluation whatever the
  /// machine's load. The default: as much as a value evaluation.
  virtual double gradientCost() const { return 1.0; }
};

/// max(0, max g, max |h|, bound violations): how far x is from feasible.
double maxViolation(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& values);
/// max(0, bound violations) of x alone.
double boundViolation(const NlpProblem& problem, const Eigen::VectorXd& x);

}  // namespace mbsopt
