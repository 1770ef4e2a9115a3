// The adapters' shared bookkeeping: evaluations cached by design vector (NLopt's MMA and CCSAQ ask
// for a point's gradient after its value, Ipopt asks for f, g, ∇f and the Jacobian separately; none
// of them pays twice for a point), the evaluation counts, the best point seen, and the history.
#pragma once

#include <deque>

#include "optimizers/nlp_problem.hpp"
#include "optimizers/optimizer.hpp"

namespace mbsopt {

/// The first-order residual above which a "converged" point is not taken as optimal: loose, because
/// the algorithms' own tolerances are on steps and costs, and a max over a time grid is only
/// piecewise smooth; a point where no active constraint balances the cost gradient scores 1.
inline constexpr double kFirstOrderTolerance = 1e-2;

class EvaluationCache {
 public:
  EvaluationCache(NlpProblem& problem, const OptimizerOptions& options) : problem_(problem), options_(options) {}

  NlpProblem& problem() { return problem_; }

  /// The values at x (with gradients when asked), from the cache when x was evaluated before.
  const NlpEvaluation& at(const Eigen::VectorXd& x, bool gradients);
  /// Passes the hint on to the problem (NlpProblem::anticipate) unless x's values are known.
  void anticipate(const Eigen::VectorXd& x);

  /// Appends an iteration at x to `result.history` and reports it, unless x is the last one recorded.
  void recordIteration(const Eigen::VectorXd& x, OptimizerResult& result);
  /// The same from the algorithm's own figures (Ipopt 3.11's callback does not hand over x): the
  /// iterate is taken to be the newest cached point with that cost (to round-off), if there is one.
  void recordIteration(double cost, double max_violation, double step, OptimizerResult& result);

  /// Fills the result's point, cost, violation and counts: the best point evaluated (feasible
  /// within the options' tolerance with the lowest cost, else the least violation).
  void finish(OptimizerResult& result) const;

  /// After finish(): the algorithm's verdict, checked. An infeasible best point is a failure that
  /// says so; a "converged" point that fails the first-order conditions (residual above
  /// kFirstOrderTolerance, first_order_check.hpp) is a failure that says the algorithm could not
  /// move from it. May cost one gradient evaluation at the best point.
  void review(OptimizerResult& result);

  long valueEvaluations() const { return value_evaluations_; }
  long gradientEvaluations() const { return gradient_evaluations_; }

 private:
  struct Entry {
    Eigen::VectorXd x;
    NlpEvaluation values;
    bool has_gradients = false;
    double violation = 0.0;
  };
  void consider(const Entry& entry);
  void record(double cost, double max_violation, double step, const Eigen::VectorXd& x, OptimizerResult& result);

  NlpProblem& problem_;
  const OptimizerOptions& options_;
  std::deque<Entry> entries_;  ///< the most recent points, newest first
  long value_evaluations_ = 0, gradient_evaluations_ = 0;
  bool has_best_ = false;
  Entry best_;
  Eigen::VectorXd previous_iterate_;
};


}  // namespace mbsopt
