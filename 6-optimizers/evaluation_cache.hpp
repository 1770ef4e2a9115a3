// The adapters' shared bookkeeping: evaluations cached by design vector (NLopt's MMA and CCSAQ ask
// for a point's gradient after its value, Ipopt asks for f, g, ∇f and the Jacobian separately; none
// of them pays twice for a point), the evaluation counts, the best point seen, and the history.
#pragma once

#include <chrono>
#include <deque>
#include <stdexcept>
#include <string>

#include "mbsopt/optimizers/nlp_problem.hpp"
#include "mbsopt/optimizers/optimizer.hpp"

namespace mbsopt {

/// The first-order residual above which a "converged" point is not taken as optimal: loose, because
/// the algorithms' own tolerances are on steps and costs, and a max over a time grid is only
/// piecewise smooth; a point where no active constraint balances the cost gradient scores 1.
inline constexpr double kFirstOrderTolerance = 1e-2;

/// What EvaluationCache::at throws instead of an evaluation beyond the run's Budget; each adapter
/// stops its algorithm on it as on any failed evaluation, and conclude() then names the limit.
struct BudgetSpent : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class EvaluationCache {
 public:
  /// The run's wall-time budget counts from here.
  EvaluationCache(NlpProblem& problem, const OptimizerOptions& options)
      : problem_(problem), options_(options), start_time_(std::chrono::steady_clock::now()) {}

  NlpProblem& problem() { return problem_; }

  /// The values at x (with gradients when asked), from the cache when x was evaluated before.
  /// Throws BudgetSpent, evaluating nothing, when the evaluation would take the run beyond
  /// options.budget: its simulation-equivalents (1 for the values of a new point, plus
  /// NlpProblem::gradientCost() for gradients), or its wall time (already spent).
  const NlpEvaluation& at(const Eigen::VectorXd& x, bool gradients);
  /// Why the budget refused an evaluation; empty while it has not.
  const std::string& budgetSpent() const { return budget_spent_; }
  /// Passes the hint on to the problem (NlpProblem::anticipate) unless x's values are known.
  void anticipate(const Eigen::VectorXd& x);

  /// Appends an iteration at x to `result.history` and reports it, unless x is the last one recorded.
  void recordIteration(const Eigen::VectorXd& x, OptimizerResult& result);
  /// The same from the algorithm's own figures (Ipopt 3.11's callback does not hand over x): the
  /// iterate is taken to be the newest cached point with that cost (to round-off), if there is one.
  void recordIteration(double cost, double max_violation, double step, OptimizerResult& result);

  /// Ends a run whose algorithm has set result.status and result.message: fills the counts and the
  /// reported point (ReportedPoint: the algorithm's final point `final_point` where its own test
  /// passed there, the point is feasible and it meets the first-order conditions, else the cheapest
  /// feasible point, else the least infeasible). A run the budget stopped has status MaxIterations,
  /// its message naming the limit (whatever the algorithm made of the refusal). A run whose every
  /// point is infeasible, or that converged at an infeasible point, is a failure that says so; so is
  /// a "converged" point that fails the first-order conditions (residual above kFirstOrderTolerance,
  /// first_order_check.hpp). May cost a gradient evaluation at the final point, outside the budget.
  /// `final_point` empty: the algorithm did not say (the cheapest feasible point is checked).
  void conclude(OptimizerResult& result, const Eigen::VectorXd& final_point);

  /// The last iterate recorded (recordIteration) whose transcription held within the feasibility
  /// tolerance; empty before the first.
  const Eigen::VectorXd& lastFeasibleIterate() const { return last_feasible_iterate_; }

  long valueEvaluations() const { return value_evaluations_; }
  long gradientEvaluations() const { return gradient_evaluations_; }

 private:
  struct Entry {
    Eigen::VectorXd x;
    NlpEvaluation values;
    bool has_gradients = false;
    double violation = 0.0;  ///< maxViolation
    /// ≤ 1: feasible as the problem judges it (its own excess over tolerance, or the transcription's
    /// violation over the feasibility tolerance where it has none; and the bounds, so measured).
    double infeasibility = 0.0;
    double cost = 0.0;  ///< the problem's own cost (reported_cost, or f)
    bool feasible() const { return infeasibility <= 1.0; }
    /// Whether this entry is to be reported rather than `best` (ReportedPoint's order).
    bool betterThan(const Entry& best) const;
  };
  /// Keeps the best point evaluated, and the best iterate (a point recordIteration recorded).
  void consider(const Entry& entry);
  void considerIterate(const Entry& entry);
  /// The entry at x: the cached one, or x evaluated now (outside the budget).
  Entry entryAt(const Eigen::VectorXd& x);
  /// The first-order check at x with its gradients (evaluated outside the budget when not cached).
  FirstOrderCheck firstOrderAt(const Eigen::VectorXd& x);
  /// Fills the result's point and values from an entry.
  static void report(const Entry& entry, ReportedPoint kind, OptimizerResult& result);
  /// The reported point by ReportedPoint's rule, and the verdict on the run it ends (conclude()).
  void reportPoint(OptimizerResult& result, const Eigen::VectorXd& final_point);
  /// Throws BudgetSpent when an evaluation costing `cost` simulation-equivalents would exceed the budget.
  void refuseBeyondBudget(double cost);
  void record(double cost, double max_violation, double step, const Eigen::VectorXd& x, double reported_cost,
              OptimizerResult& result);

  NlpProblem& problem_;
  const OptimizerOptions& options_;
  std::deque<Entry> entries_;  ///< the most recent points, newest first
  const std::chrono::steady_clock::time_point start_time_;
  long value_evaluations_ = 0, gradient_evaluations_ = 0;
  double simulation_equivalents_ = 0.0;
  std::string budget_spent_;
  bool reviewing_ = false;  ///< conclude() evaluates: outside the budget
  bool has_best_ = false, has_best_iterate_ = false;
  Entry best_, best_iterate_;
  Eigen::VectorXd previous_iterate_, last_feasible_iterate_;
};


}  // namespace mbsopt
