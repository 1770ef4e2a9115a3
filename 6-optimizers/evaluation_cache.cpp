#include "mbsopt/optimizers/evaluation_cache.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "mbsopt/optimizers/first_order_check.hpp"

namespace mbsopt {

namespace {
constexpr std::size_t kCachedPoints = 8;

std::string shortNumber(double value) {
  std::ostringstream out;
  out << std::setprecision(4) << value;
  return out.str();
}
}  // namespace

double boundViolation(const NlpProblem& problem, const Eigen::VectorXd& x) {
  const Eigen::VectorXd lower = problem.lowerBounds(), upper = problem.upperBounds();
  double violation = 0.0;
  for (Eigen::Index j = 0; j < x.size(); ++j) violation = std::max({violation, lower[j] - x[j], x[j] - upper[j]});
  return violation;
}

double maxViolation(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& values) {
  const Eigen::Index inequalities = problem.inequalityCount();
  double violation = boundViolation(problem, x);
  for (Eigen::Index i = 0; i < values.constraints.size(); ++i)
    violation = std::max(violation, i < inequalities ? values.constraints[i] : std::abs(values.constraints[i]));
  return violation;
}

const NlpEvaluation& EvaluationCache::at(const Eigen::VectorXd& x, bool gradients) {
  // The best point stays known however many points came after it (the verdict asks for it).
  if (has_best_ && best_.x == x && (best_.has_gradients || !gradients)) return best_.values;
  const auto hit = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.x == x; });
  if (hit != entries_.end() && (hit->has_gradients || !gradients)) return hit->values;
  const bool values_known = hit != entries_.end() || (has_best_ && best_.x == x);
  // The gradients of a known point reuse its simulation: they cost their own share only.
  const double cost = (values_known ? 0.0 : 1.0) + (gradients ? problem_.gradientCost() : 0.0);
  refuseBeyondBudget(cost);
  if (hit != entries_.end()) entries_.erase(hit);
  Entry entry{x, {}, gradients};
  problem_.evaluate(x, gradients, entry.values);
  if (!values_known) ++value_evaluations_;
  if (gradients) ++gradient_evaluations_;
  simulation_equivalents_ += cost;
  const double tolerance = options_.feasibility_tolerance;
  entry.violation = maxViolation(problem_, x, entry.values);
  const double own = entry.values.excess_over_tolerance;
  entry.infeasibility = std::max(std::isnan(own) ? entry.violation / tolerance : own, boundViolation(problem_, x) / tolerance);
  entry.cost = std::isnan(entry.values.reported_cost) ? entry.values.cost : entry.values.reported_cost;
  consider(entry);
  entries_.push_front(std::move(entry));
  if (entries_.size() > kCachedPoints) entries_.pop_back();
  return entries_.front().values;
}

void EvaluationCache::refuseBeyondBudget(double cost) {
  if (reviewing_) return;
  const Budget& budget = options_.budget;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time_).count();
  if (simulation_equivalents_ + cost > budget.simulation_equivalents)
    budget_spent_ = "the budget of " + shortNumber(budget.simulation_equivalents) + " simulation-equivalents is spent (" +
                    shortNumber(simulation_equivalents_) + " spent, the next evaluation costs " + shortNumber(cost) + ")";
  else if (elapsed >= budget.wall_time_s)
    budget_spent_ = "the budget of " + shortNumber(budget.wall_time_s) + " s wall time is spent";
  else
    return;
  throw BudgetSpent(budget_spent_);
}

void EvaluationCache::anticipate(const Eigen::VectorXd& x) {
  const bool known = (has_best_ && best_.x == x) ||
                     std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.x == x; });
  if (!known) problem_.anticipate(x);
}

bool EvaluationCache::Entry::betterThan(const Entry& best) const {
  // The cheapest feasible point, the latest of equals; before any is feasible, the least infeasible.
  return (feasible() && (!best.feasible() || cost <= best.cost)) ||
         (!feasible() && !best.feasible() && infeasibility < best.infeasibility) ||
         (x == best.x && has_gradients);  // the best point, now with gradients
}

void EvaluationCache::consider(const Entry& entry) {
  if (has_best_ && !entry.betterThan(best_)) return;
  best_ = entry;
  has_best_ = true;
}

void EvaluationCache::considerIterate(const Entry& entry) {
  if (has_best_iterate_ && !entry.betterThan(best_iterate_)) return;
  best_iterate_ = entry;
  has_best_iterate_ = true;
}

void EvaluationCache::recordIteration(const Eigen::VectorXd& x, OptimizerResult& result) {
  if (previous_iterate_.size() == x.size() && previous_iterate_ == x) return;  // asked again for the same point
  const NlpEvaluation& values = at(x, false);
  considerIterate(entryAt(x));  // cached by at(): no evaluation
  const double step = previous_iterate_.size() == x.size() ? (x - previous_iterate_).cwiseAbs().maxCoeff() : 0.0;
  previous_iterate_ = x;
  const double violation = maxViolation(problem_, x, values);
  if (violation <= options_.feasibility_tolerance) last_feasible_iterate_ = x;
  record(values.cost, violation, step, x, values.reported_cost, result);
}

void EvaluationCache::recordIteration(double cost, double max_violation, double step, OptimizerResult& result) {
  const auto iterate = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) {
    return std::abs(e.values.cost - cost) <= 1e-14 * std::max(1.0, std::abs(cost));  // Ipopt's unscaling
  });
  const bool known = iterate != entries_.end();
  if (known) considerIterate(*iterate);
  record(cost, max_violation, step, known ? iterate->x : Eigen::VectorXd(),
         known ? iterate->values.reported_cost : std::numeric_limits<double>::quiet_NaN(), result);
}

void EvaluationCache::record(double cost, double max_violation, double step, const Eigen::VectorXd& x,
                             double reported_cost, OptimizerResult& result) {
  const IterationRecord record{static_cast<int>(result.history.size()), cost, max_violation, step, value_evaluations_,
                               gradient_evaluations_, simulation_equivalents_,
                               x.size() > 0 && std::isnan(reported_cost) ? cost : reported_cost, x};
  result.history.push_back(record);
  if (options_.on_iteration) options_.on_iteration(record);
}

namespace {

/// Sets a flag for its lifetime, however the scope ends.
class FlagFor {
 public:
  explicit FlagFor(bool& flag) : flag_(flag) { flag_ = true; }
  ~FlagFor() { flag_ = false; }
  FlagFor(const FlagFor&) = delete;
  FlagFor& operator=(const FlagFor&) = delete;

 private:
  bool& flag_;
};

}  // namespace

EvaluationCache::Entry EvaluationCache::entryAt(const Eigen::VectorXd& x) {
  if (has_best_ && best_.x == x) return best_;
  const auto hit = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.x == x; });
  if (hit != entries_.end()) return *hit;
  const FlagFor reviewing(reviewing_);
  at(x, false);
  return entries_.front();
}

FirstOrderCheck EvaluationCache::firstOrderAt(const Eigen::VectorXd& x) {
  const double active = std::max(100.0 * options_.feasibility_tolerance, 1e-6);
  const FlagFor reviewing(reviewing_);  // the verdict's gradient is not the run's: no budget refuses it
  return firstOrderCheck(problem_, x, at(x, true), active);
}

void EvaluationCache::report(const Entry& entry, ReportedPoint kind, OptimizerResult& result) {
  result.x = entry.x;
  result.cost = entry.values.cost;
  result.reported_cost = entry.cost;
  result.max_violation = entry.violation;
  result.excess_over_tolerance = entry.values.excess_over_tolerance;
  result.reported = kind;
}

void EvaluationCache::conclude(OptimizerResult& result, const Eigen::VectorXd& final_point) {
  result.iterations = static_cast<int>(result.history.size());
  if (!budget_spent_.empty() && result.status != OptimizerStatus::Unsupported) {
    result.status = OptimizerStatus::MaxIterations;
    if (result.message.find(budget_spent_) == std::string::npos) result.message += "; stopped: " + budget_spent_;
  }
  result.final_point = final_point;
  if (has_best_) reportPoint(result, final_point);
  result.value_evaluations = value_evaluations_;
  result.gradient_evaluations = gradient_evaluations_;
  result.simulation_equivalents = simulation_equivalents_;
}

void EvaluationCache::reportPoint(OptimizerResult& result, const Eigen::VectorXd& final_point) {
  // Among the iterates, which the history records and the plots show; the points evaluated only
  // where the algorithm recorded none.
  const Entry cheapest = has_best_iterate_ ? best_iterate_ : best_;
  report(cheapest, cheapest.feasible() ? ReportedPoint::CheapestFeasible : ReportedPoint::LeastInfeasible, result);
  if (cheapest.feasible()) {
    result.cheapest_x = cheapest.x;
    result.cheapest_cost = cheapest.cost;
  }
  if (result.status == OptimizerStatus::Unsupported || result.status == OptimizerStatus::Failed) return;
  if (!cheapest.feasible()) {
    result.status = OptimizerStatus::Failed;
    result.message += "; no point it evaluated is feasible (the closest is " + shortNumber(cheapest.infeasibility) +
                      " times the largest allowed excess)";
    return;
  }
  if (result.status != OptimizerStatus::Converged) return;
  const bool said = final_point.size() == cheapest.x.size();
  const Entry final = said ? entryAt(final_point) : cheapest;
  if (!final.feasible()) {
    result.status = OptimizerStatus::Failed;
    result.message += "; its own test passed at a point beyond the problem's tolerances (" +
                      shortNumber(final.infeasibility) + " times the largest allowed excess)";
    return;
  }
  const FirstOrderCheck check = firstOrderAt(final.x);
  if (check.residual > kFirstOrderTolerance) {
    result.status = OptimizerStatus::Failed;
    result.message += "; its own test passed at a point that is not first-order optimal (KKT residual " +
                      shortNumber(check.residual) + ")";
    if (final.x == cheapest.x) result.first_order = check;
    return;
  }
  report(final, said ? ReportedPoint::Final : ReportedPoint::CheapestFeasible, result);
  result.first_order = check;
}

}  // namespace mbsopt
