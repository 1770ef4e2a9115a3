#include "mbsopt/optimizers/sdcc.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "mbsopt/optimizers/evaluation_cache.hpp"

namespace mbsopt {

namespace {

/// δb₁ below this fraction of ‖W^{-1/2} l₀‖ is round-off of the projection, not a direction.
constexpr double kNegligibleDescent = 1e-12;
/// A residual of the compensation's least-squares solve above this fraction of max(1, ‖Ψ̃‖∞): the
/// active set is inconsistent (a consistent one leaves round-off, orders of magnitude below).
constexpr double kInconsistentCompensation = 1e-9;

/// The first of the variables' bounds among the constraints.
Eigen::Index firstBound(const ConstraintLinearization& constraints) {
  return constraints.values.size() - constraints.bound_count;
}

/// (7): every equality, and the inequalities with Ψᵢ ≥ −ε, the variables' bounds excepted.
std::vector<Eigen::Index> epsilonActive(const ConstraintLinearization& constraints, double epsilon) {
  std::vector<Eigen::Index> active;
  for (Eigen::Index i = 0; i < firstBound(constraints); ++i)
    if (i < constraints.equality_count || constraints.values[i] >= -epsilon) active.push_back(i);
  return active;
}

/// The bounds within ε that `step` would cross (ΨᵢBound + step's change > 0 for a bound at Ψᵢ ≥ −ε),
/// added to `active`; false when there is none. (7) takes every bound within ε as an equality of the
/// projection (11): a variable at its bound then could not leave it even where the compensation
/// needed it to, and with more active constraints than variables (both variables of
/// problems/suite/quarter_car.yaml at their lower bounds beside two violated travel constraints) the
/// least-squares compensation moved nothing. A bound holds the variable only when the step pushes
/// it out, as in a projected-gradient method on a box.
bool addCrossedBounds(const ConstraintLinearization& constraints, const Eigen::VectorXd& step, double epsilon,
                      std::vector<Eigen::Index>& active) {
  bool added = false;
  for (Eigen::Index i = firstBound(constraints); i < constraints.values.size(); ++i) {
    if (constraints.values[i] < -epsilon || std::find(active.begin(), active.end(), i) != active.end()) continue;
    if (constraints.values[i] + constraints.gradients.col(i).dot(step) > 0.0) {
      active.push_back(i);
      added = true;
    }
  }
  return added;
}

/// The projection (11) in the variables W^{1/2}b, where L becomes A = W^{-1/2}L and LᵀW⁻¹L = AᵀA:
/// the rank-revealing solves are on A itself (its condition number, not its square), and dependent
/// active constraints get the least-norm multipliers instead of a singular solve.
struct ScaledProjection {
  Eigen::VectorXd first_multipliers;   ///< μ₁
  Eigen::VectorXd second_multipliers;  ///< μ₂ = (LᵀW⁻¹L)⁻¹Ψ̃, which compensation adds to μ₁ (11)
  Eigen::VectorXd descent;             ///< W^{1/2}δb₁
  Eigen::VectorXd compensation;        ///< W^{1/2}δb₂
};

ScaledProjection project(const Eigen::VectorXd& scaled_cost_gradient, const Eigen::MatrixXd& scaled_gradients,
                         const Eigen::VectorXd& active_values) {
  if (scaled_gradients.cols() == 0)  // no active constraint: plain steepest descent (6); Eigen's COD needs a column
    return {Eigen::VectorXd(0), Eigen::VectorXd(0), -scaled_cost_gradient,
            Eigen::VectorXd::Zero(scaled_cost_gradient.size())};
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> of_a(scaled_gradients),
      of_a_transposed(scaled_gradients.transpose());
  ScaledProjection p;
  p.first_multipliers = -of_a.solve(scaled_cost_gradient);  // μ₁ = −(LᵀW⁻¹L)⁻¹LᵀW⁻¹l₀ = −A⁺W^{-1/2}l₀
  p.descent = -(scaled_cost_gradient + scaled_gradients * p.first_multipliers);  // δb₁ = −W⁻¹(l₀ + Lμ₁)
  const Eigen::VectorXd pulled_back = of_a_transposed.solve(active_values);  // A(AᵀA)⁻¹Ψ̃ = A⁺ᵀΨ̃
  p.compensation = -pulled_back;  // δb₂ = −W⁻¹L(LᵀW⁻¹L)⁻¹Ψ̃
  p.second_multipliers = of_a.solve(pulled_back);  // (AᵀA)⁻¹Ψ̃ = A⁺A⁺ᵀΨ̃
  return p;
}

/// (10) shared by the W-orthogonal parts: ‖t δb₁ + φ δb₂‖²_W = t²‖δb₁‖²_W + φ²‖δb₂‖²_W = ξ².
/// The compensation comes first (φ = 1 when it fits); t = 1/(2γ) of (11) takes what is left.
void splitStepBound(double step_bound, double descent_norm, double compensation_norm, bool descent_negligible,
                    SdccStep& step) {
  if (compensation_norm >= step_bound) {  // no γ ≥ 0 solves (10)-(11): compensate as far as ξ allows
    step.scale_compensation = step_bound / compensation_norm;
    step.scale_descent = 0.0;
    return;
  }
  step.scale_compensation = 1.0;
  step.scale_descent =
      descent_negligible ? 0.0 : std::sqrt(step_bound * step_bound - compensation_norm * compensation_norm) / descent_norm;
}

/// Vectors with the signs of the step's multipliers μ̃ = μ₁ + 2γφμ₂ (11): t μ₁ + φ μ₂ with t = 1/(2γ);
/// μ₂ alone when the compensation takes all of ξ (γ → ∞); μ₁ alone when there is no descent (γ = 0).
Eigen::VectorXd multiplierSigns(const ScaledProjection& p, const SdccStep& step) {
  if (step.scale_descent > 0.0)
    return step.scale_descent * p.first_multipliers + step.scale_compensation * p.second_multipliers;
  return step.scale_compensation < 1.0 ? p.second_multipliers : p.first_multipliers;
}

/// The position in `active` of the general inequality (neither an equality nor a variable's bound,
/// those from `first_bound` on) with the most negative of `signs` among those `eligible(k)` admits,
/// or −1. Bounds never leave: they are held only where the step crosses them (addCrossedBounds), so
/// each pass of sdccStep drops an inequality or holds a bound, never the reverse, and it ends.
template <class Eligible>
Eigen::Index mostNegative(const std::vector<Eigen::Index>& active, const Eigen::VectorXd& signs,
                          Eigen::Index equality_count, Eigen::Index first_bound, Eligible eligible) {
  Eigen::Index leaving = -1;
  for (Eigen::Index k = 0; k < signs.size(); ++k) {
    const Eigen::Index i = active[static_cast<std::size_t>(k)];
    if (i >= equality_count && i < first_bound && signs[k] < 0.0 && eligible(k) &&
        (leaving < 0 || signs[k] < signs[leaving]))
      leaving = k;
  }
  return leaving;
}

/// The inequality with the most negative multiplier (11), which leaves; −1 if none.
Eigen::Index leavingInequality(const std::vector<Eigen::Index>& active, const Eigen::VectorXd& signs,
                               Eigen::Index equality_count, Eigen::Index first_bound) {
  return mostNegative(active, signs, equality_count, first_bound, [](Eigen::Index) { return true; });
}

/// Where the compensation cannot zero every active constraint (more of them than the variables can
/// meet, the least-squares δb₂ leaves a residual), the satisfied inequality (Ψᵢ < 0) with the most
/// negative compensation multiplier μ₂, which leaves; −1 when the compensation meets them all or no
/// such inequality is active. Compensating a satisfied inequality to zero pulls it onto its
/// boundary; in an inconsistent set that cost the violated ones their mending, and the step mended
/// nothing (problems/suite/train_couplers.yaml: 19 equalities and both sides of the cost's extreme
/// for 20 variables, δb₁ zero, ξ shrinking to its floor).
Eigen::Index leavingForTheCompensation(const std::vector<Eigen::Index>& active, const ScaledProjection& p,
                                       const Eigen::MatrixXd& scaled_gradients, const Eigen::VectorXd& active_values,
                                       Eigen::Index equality_count, Eigen::Index first_bound) {
  if (active_values.size() == 0) return -1;
  const Eigen::VectorXd residual = scaled_gradients.transpose() * p.compensation + active_values;
  if (!(residual.cwiseAbs().maxCoeff() > kInconsistentCompensation * std::max(1.0, active_values.cwiseAbs().maxCoeff())))
    return -1;
  return mostNegative(active, p.second_multipliers, equality_count, first_bound,
                      [&](Eigen::Index k) { return active_values[k] < 0.0; });
}

}  // namespace

SdccStep sdccStep(const Eigen::VectorXd& cost_gradient, const ConstraintLinearization& constraints,
                  const Eigen::VectorXd& weights, double epsilon, double step_bound) {
  const Eigen::VectorXd root = weights.cwiseSqrt();  // W^{1/2}
  const Eigen::VectorXd scaled_cost_gradient = cost_gradient.cwiseQuotient(root);
  SdccStep step;
  step.active = epsilonActive(constraints, epsilon);  // (7)
  for (;;) {  // each pass drops an inequality or holds a bound (mostNegative), so it ends
    const Eigen::MatrixXd scaled_gradients =
        root.cwiseInverse().asDiagonal() * constraints.gradients(Eigen::all, step.active);  // (9): l̃
    const ScaledProjection p = project(scaled_cost_gradient, scaled_gradients, constraints.values(step.active));
    const double descent_norm = p.descent.norm();
    splitStepBound(step_bound, descent_norm, p.compensation.norm(),
                   descent_norm <= kNegligibleDescent * scaled_cost_gradient.norm(), step);
    Eigen::Index leaving =
        leavingInequality(step.active, multiplierSigns(p, step), constraints.equality_count, firstBound(constraints));
    if (leaving < 0)
      leaving = leavingForTheCompensation(step.active, p, scaled_gradients, constraints.values(step.active),
                                          constraints.equality_count, firstBound(constraints));
    if (leaving < 0) {
      step.multipliers = p.first_multipliers;
      step.descent = p.descent.cwiseQuotient(root);
      step.compensation = p.compensation.cwiseQuotient(root);
      step.step = step.scale_descent * step.descent + step.scale_compensation * step.compensation;
      if (!addCrossedBounds(constraints, step.step, epsilon, step.active)) return step;
      continue;  // with the bounds it would cross held
    }
    step.active.erase(step.active.begin() + leaving);  // a negative multiplier: the constraint leaves (11)
  }
}

namespace {

/// The problem's constraints at x as (14) has them: [h; g; x − upper; lower − x].
ConstraintLinearization linearize(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& values) {
  const Eigen::Index n = x.size(), inequalities = problem.inequalityCount(), equalities = problem.equalityCount();
  ConstraintLinearization c;
  c.equality_count = equalities;
  c.bound_count = 2 * n;
  c.values.resize(equalities + inequalities + 2 * n);
  c.values << values.constraints.tail(equalities), values.constraints.head(inequalities), x - problem.upperBounds(),
      problem.lowerBounds() - x;
  c.gradients.resize(n, c.values.size());
  c.gradients << values.constraint_jacobian.bottomRows(equalities).transpose(),
      values.constraint_jacobian.topRows(inequalities).transpose(), Eigen::MatrixXd::Identity(n, n),
      -Eigen::MatrixXd::Identity(n, n);
  return c;
}

/// The max violation the linearization (9) predicts after the step δb.
double predictedViolation(const ConstraintLinearization& c, const Eigen::VectorXd& step) {
  const Eigen::VectorXd after = c.values + c.gradients.transpose() * step;
  const double equalities = c.equality_count > 0 ? after.head(c.equality_count).cwiseAbs().maxCoeff() : 0.0;
  const Eigen::Index inequalities = after.size() - c.equality_count;
  return std::max({0.0, equalities, inequalities > 0 ? after.tail(inequalities).maxCoeff() : 0.0});
}

std::string number(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

Eigen::VectorXd checkedWeights(const SdccSettings& settings, Eigen::Index n) {
  if (settings.weights.size() == 0) return Eigen::VectorXd::Ones(n);
  if (settings.weights.size() != n || !(settings.weights.array() > 0.0).all() || !settings.weights.allFinite())
    throw std::invalid_argument("SDCC: the weights W must be " + std::to_string(n) +
                                " positive finite numbers, one per design variable");
  return settings.weights;
}

/// One run: the current design and its linearization, the step bound ξ and the merit's penalty ρ.
class SdccRun {
 public:
  SdccRun(NlpProblem& problem, const OptimizerOptions& options, const SdccSettings& settings, OptimizerResult& result)
      : problem_(problem),
        options_(options),
        settings_(settings),
        result_(result),
        cache_(problem, options),
        weights_(checkedWeights(settings, problem.variableCount())),
        step_bound_(settings.initial_step_bound),
        penalty_(settings.initial_penalty) {}

  void run() {
    // The start is clipped to the bounds: no point outside them is evaluated.
    const Eigen::VectorXd start = problem_.start().cwiseMax(problem_.lowerBounds()).cwiseMin(problem_.upperBounds());
    try {
      accept(start, cache_.at(start, true));
    } catch (const std::exception& e) {
      return stop(OptimizerStatus::Failed, std::string("the start could not be evaluated: ") + e.what());
    }
    stationarity_scale_ = std::max(1.0, values_.cost_gradient.cwiseQuotient(weights_.cwiseSqrt()).norm());
    for (int trial = 0;; ++trial) {
      const SdccStep step =
          sdccStep(values_.cost_gradient, constraints_, weights_, settings_.active_set_epsilon, step_bound_);
      const double stationarity = step.descent.cwiseProduct(weights_.cwiseSqrt()).norm();  // ‖δb₁‖_W
      const std::string where = "‖δb₁‖_W = " + number(stationarity) + ", max violation " + number(violation_);
      if (stationarity <= settings_.stationarity_tolerance * stationarity_scale_ &&
          violation_ <= options_.feasibility_tolerance)
        return stop(OptimizerStatus::Converged, "a feasible KKT point: " + where);
      if (!cache_.budgetSpent().empty()) return stop(OptimizerStatus::MaxIterations, cache_.budgetSpent() + ", " + where);
      if (trial == options_.max_iterations)
        return stop(OptimizerStatus::MaxIterations, std::to_string(trial) + " trial steps, " + where);
      if (step_bound_ < stepFloor()) {
        // No step longer than the floor lowers the merit (NLopt's xtol_rel for a trust region). At a
        // feasible point that is the end: where the active constraints' gradients vanish or jump (the
        // paper's ∫⟨φ⟩dt on its boundary, a grid maximum at a kink) ‖δb₁‖_W need not, and no KKT
        // point can be certified; at an infeasible one the run failed.
        const std::string floor = "the step bound ξ fell below " + number(stepFloor()) +
                                  " (xtol_rel max(1, ‖b‖_W), at least " + number(settings_.min_step_bound) + ")";
        if (violation_ <= options_.feasibility_tolerance)
          return stop(OptimizerStatus::Converged, floor + " at a feasible point, no shorter step lowering the merit: " + where);
        return stop(OptimizerStatus::Failed, floor + " at an infeasible point: " + where);
      }
      tryStep(step);
    }
  }

  void finish() {
    cache_.conclude(result_, x_);
  }

 private:
  void accept(const Eigen::VectorXd& x, const NlpEvaluation& values) {
    rejected_here_ = false;
    x_ = x;
    values_ = values;
    constraints_ = linearize(problem_, x_, values_);
    violation_ = maxViolation(problem_, x_, values_);
    cache_.recordIteration(x_, result_);
  }

  /// A trial: x + δb clipped to the bounds, and the merit change the linearization (8)-(9) predicts
  /// for it with the penalty ρ.
  struct Trial {
    Eigen::VectorXd point;
    double predicted = 0.0;
  };
  /// The trial of `step` with the penalty raised as it needs (raisedPenalty), into `penalty`.
  Trial plannedTrial(const SdccStep& step, double& penalty) const {
    Trial t;
    t.point = (x_ + step.step).cwiseMax(problem_.lowerBounds()).cwiseMin(problem_.upperBounds());
    const Eigen::VectorXd taken = t.point - x_;
    const double cost_change = values_.cost_gradient.dot(taken);                         // (8)
    const double violation_change = predictedViolation(constraints_, taken) - violation_;  // (9)
    penalty = raisedPenalty(penalty, step, cost_change, violation_change, settings_);
    t.predicted = cost_change + penalty * violation_change;
    return t;
  }
  /// ρ kept at least penalty_factor × ‖μ₁‖₁ (an exact penalty needs ρ > ‖μ‖₁), and, for a step that
  /// lowers the predicted violation, at least penalty_factor × its cost change over that decrease:
  /// then the merit predicts a decrease. Without that, a compensation whose cost rises more than
  /// ρ × the violation it removes (the multipliers of the ε-active set need not cover a violated
  /// equality) predicted none at any ξ, and ξ shrank to its floor at an infeasible point
  /// (problems/suite/spring_return.yaml).
  static double raisedPenalty(double penalty, const SdccStep& step, double cost_change, double violation_change,
                              const SdccSettings& settings) {
    penalty = std::max(penalty, settings.penalty_factor * step.multipliers.lpNorm<1>());
    if (violation_change < 0.0 && cost_change > 0.0)
      penalty = std::max(penalty, settings.penalty_factor * cost_change / -violation_change);
    return penalty;
  }

  /// The point the next trials would evaluate should `rejected` be rejected: ξ shrunk, and shrunk
  /// again past the steps that predict no decrease or lead to the rejected point again (the bounds
  /// clip both alike; they evaluate nothing), with the penalty as it would grow. Computed as tryStep
  /// computes them, so it is the very point when it comes to that; none when ξ would first fall
  /// below its minimum.
  std::optional<Eigen::VectorXd> pointAfterRejection(const Eigen::VectorXd& rejected) const {
    double penalty = penalty_;
    for (double bound = step_bound_ * settings_.shrink_factor; bound >= stepFloor(); bound *= settings_.shrink_factor) {
      const SdccStep step = sdccStep(values_.cost_gradient, constraints_, weights_, settings_.active_set_epsilon, bound);
      Trial next = plannedTrial(step, penalty);
      if (next.predicted < 0.0 && next.point != rejected) return std::move(next.point);
    }
    return std::nullopt;
  }

  /// Evaluates x + δb (clipped to the bounds) and accepts it when the merit f + ρ·violation falls
  /// by at least `acceptance_ratio` of what the linearization (8)-(9) predicts; adapts ξ. Once a
  /// trial from the current point has been rejected, the next ones are likely to be too (ξ halves
  /// until the linearization holds), so from then on the problem is told first which point a
  /// rejection would lead to (NlpProblem::anticipate); not before, where it would mostly simulate
  /// in vain beside an accepted trial.
  void tryStep(const SdccStep& step) {
    const Trial trial = plannedTrial(step, penalty_);
    if (!(trial.predicted < 0.0)) return shrink();  // nothing to gain at this ξ (e.g. the bounds clip the step away)
    if (rejected_here_)
      if (const std::optional<Eigen::VectorXd> next = pointAfterRejection(trial.point)) cache_.anticipate(*next);
    try {
      // Values first: a rejected trial needs no gradient (the accepted one's reuses its simulation).
      const NlpEvaluation& values = cache_.at(trial.point, false);
      const double achieved = values.cost + penalty_ * maxViolation(problem_, trial.point, values) -
                              (values_.cost + penalty_ * violation_);
      const double ratio = achieved / trial.predicted;
      if (!(ratio >= settings_.acceptance_ratio)) return reject();  // NaN is rejected too
      accept(trial.point, cache_.at(trial.point, true));
      if (ratio >= settings_.growth_ratio) step_bound_ *= settings_.growth_factor;
    } catch (const BudgetSpent&) {
      // run() stops at its next trial
    } catch (const std::exception& e) {
      last_failure_ = e.what();
      reject();
    }
  }

  /// The smallest ξ a trial is made with: options.tolerance (NLopt's xtol_rel) times max(1, ‖b‖_W),
  /// the design variables being scaled to order 1 (a relative test alone never ends at b = 0), and
  /// at least min_step_bound.
  double stepFloor() const {
    const double size = std::max(1.0, x_.cwiseProduct(weights_.cwiseSqrt()).norm());
    return std::max(settings_.min_step_bound, options_.tolerance * size);
  }

  void shrink() { step_bound_ *= settings_.shrink_factor; }
  void reject() {
    rejected_here_ = true;
    shrink();
  }

  void stop(OptimizerStatus status, const std::string& why) {
    result_.status = status;
    result_.message = "SDCC: " + why;
    if (!last_failure_.empty()) result_.message += "; last failed evaluation: " + last_failure_;
  }

  NlpProblem& problem_;
  const OptimizerOptions& options_;
  const SdccSettings& settings_;
  OptimizerResult& result_;
  EvaluationCache cache_;
  const Eigen::VectorXd weights_;
  double step_bound_;
  double penalty_;
  double stationarity_scale_ = 1.0;
  Eigen::VectorXd x_;
  NlpEvaluation values_;
  ConstraintLinearization constraints_;
  double violation_ = 0.0;
  bool rejected_here_ = false;  ///< a trial from x_ was evaluated and rejected
  std::string last_failure_;
};

}  // namespace

SdccSettings sdccSettings(const NamedSettings& named) {
  SdccSettings settings;
  const std::vector<std::pair<std::string, double SdccSettings::*>> numbers{
      {"active_set_epsilon", &SdccSettings::active_set_epsilon}, {"initial_step_bound", &SdccSettings::initial_step_bound},
      {"shrink_factor", &SdccSettings::shrink_factor},           {"growth_factor", &SdccSettings::growth_factor},
      {"growth_ratio", &SdccSettings::growth_ratio},             {"acceptance_ratio", &SdccSettings::acceptance_ratio},
      {"min_step_bound", &SdccSettings::min_step_bound},         {"stationarity_tolerance", &SdccSettings::stationarity_tolerance},
      {"initial_penalty", &SdccSettings::initial_penalty},       {"penalty_factor", &SdccSettings::penalty_factor}};
  for (const auto& [name, value] : named) {
    if (name == "weights") {
      const std::vector<double> weights = settingNumbers(name, value);
      settings.weights = Eigen::Map<const Eigen::VectorXd>(weights.data(), static_cast<Eigen::Index>(weights.size()));
      continue;
    }
    const auto field = std::find_if(numbers.begin(), numbers.end(), [&name = name](const auto& n) { return n.first == name; });
    if (field == numbers.end()) {
      std::vector<std::string> known{"weights"};
      for (const auto& n : numbers) known.push_back(n.first);
      throwUnknownSetting("SDCC", name, known);
    }
    settings.*(field->second) = settingNumber(name, value);
  }
  const bool valid = settings.active_set_epsilon >= 0.0 && settings.initial_step_bound > 0.0 &&
                     settings.shrink_factor > 0.0 && settings.shrink_factor < 1.0 && settings.growth_factor >= 1.0 &&
                     settings.acceptance_ratio > 0.0 && settings.acceptance_ratio <= settings.growth_ratio &&
                     settings.growth_ratio < 1.0 && settings.min_step_bound > 0.0 &&
                     settings.stationarity_tolerance > 0.0 && settings.initial_penalty > 0.0 &&
                     settings.penalty_factor >= 1.0;
  if (!valid)
    throw std::invalid_argument(
        "SDCC settings out of range: need active_set_epsilon ≥ 0; initial_step_bound, min_step_bound, "
        "stationarity_tolerance, initial_penalty > 0; 0 < shrink_factor < 1 ≤ growth_factor; 0 < acceptance_ratio "
        "≤ growth_ratio < 1; penalty_factor ≥ 1");
  return settings;
}

OptimizerResult minimizeWithSdcc(NlpProblem& problem, const OptimizerOptions& options, const SdccSettings& settings) {
  OptimizerResult result;
  result.optimizer = "SDCC (steepest descent with constraint compensation)";
  SdccRun run(problem, options, settings, result);
  run.run();
  run.finish();
  return result;
}

}  // namespace mbsopt
