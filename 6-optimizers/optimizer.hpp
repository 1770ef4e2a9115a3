// One interface over every optimizer (docs/design.md §5): minimize(name, problem, options) returns the
// same record whichever algorithm ran, with a per-iteration history, and counts evaluations the way
// the design problems pay for them (value evaluations = simulations, gradient evaluations).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mbsopt/optimizers/first_order_check.hpp"
#include "mbsopt/optimizers/nlp_problem.hpp"
#include "mbsopt/optimizers/optimizer_settings.hpp"

namespace mbsopt {

enum class OptimizerStatus {
  Converged,      ///< the algorithm's own stopping test passed at a feasible point
  MaxIterations,  ///< stopped by the iteration or evaluation budget
  Failed,         ///< stopped elsewhere, or "converged" at an infeasible point: `message` says why
  Unsupported     ///< the algorithm cannot take this problem (e.g. MMA and equality constraints)
};

std::string toString(OptimizerStatus status);

/// Which evaluated point a result reports (EvaluationCache::conclude). Feasible means within the
/// problem's own tolerances (NlpEvaluation::excess_over_tolerance ≤ 1, the bounds held), cheapest the
/// least of the problem's own cost (NlpEvaluation::reported_cost).
enum class ReportedPoint {
  /// The algorithm's final point, where its own convergence test passed, feasible and first-order
  /// optimal. An earlier point may be cheaper by what the tolerances allow
  /// (OptimizerResult::cheapest_cost says).
  Final,
  /// The cheapest feasible iterate (a point the history records; the latest of equals; the cheapest
  /// point evaluated where the algorithm recorded none): the run did not converge, or its
  /// final point failed the problem's tolerances or the first-order check.
  CheapestFeasible,
  /// No point evaluated is feasible: the closest one.
  LeastInfeasible
};

std::string toString(ReportedPoint point);

struct IterationRecord {
  int iteration = 0;
  double cost = 0.0;
  double max_violation = 0.0;
  double step = 0.0;  ///< ‖x_k − x_{k−1}‖∞ (0 for the first record)
  long value_evaluations = 0;
  long gradient_evaluations = 0;
  /// value_evaluations + gradient_evaluations × NlpProblem::gradientCost(): the budget spent so far
  double simulation_equivalents = 0.0;
  /// NlpEvaluation::reported_cost at the iterate (NaN where the algorithm does not say which point it is)
  double reported_cost = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd x;  ///< the iterate (empty where the algorithm does not say which point it is)
};

/// The limits every optimizer is held to alike (EvaluationCache::at): an evaluation that would take
/// the run beyond either is not made, and the run ends with the best point so far (status
/// MaxIterations, its message naming the limit). Infinite: no limit.
struct Budget {
  /// Value evaluations plus gradient evaluations × NlpProblem::gradientCost()
  double simulation_equivalents = std::numeric_limits<double>::infinity();
  /// Since the run began [s]
  double wall_time_s = std::numeric_limits<double>::infinity();
};

struct OptimizerOptions {
  int max_iterations = 100;  ///< each algorithm's own count (NLopt: evaluations; Ipopt, SDCC: iterations)
  Budget budget;             ///< the common budget, counted alike for every algorithm
  double tolerance = 1e-6;              ///< relative, on x and on f (each algorithm's own test)
  double feasibility_tolerance = 1e-6;  ///< max violation a converged point may have
  /// Algorithm-specific settings by name, as text: SDCC's SdccSettings fields, any Ipopt option,
  /// NLopt's MMA/CCSAQ parameters (inner_maxeval, dual_ftol_rel, verbosity). A name the algorithm
  /// does not know, or a value it cannot take, is an std::invalid_argument before anything runs.
  NamedSettings settings;
  /// Called after each recorded iteration (the command's progress table); may be empty.
  std::function<void(const IterationRecord&)> on_iteration;
};

struct OptimizerResult {
  std::string optimizer;
  OptimizerStatus status = OptimizerStatus::Failed;
  std::string message;  ///< the algorithm's own words, and ours where we overrule it
  Eigen::VectorXd x;    ///< the reported point (`reported` says which)
  double cost = 0.0;    ///< f at x
  /// The problem's own cost at x (NlpEvaluation::reported_cost; f where the problem has none).
  double reported_cost = 0.0;
  double max_violation = 0.0;  ///< of the transcription at x (maxViolation)
  /// NlpEvaluation::excess_over_tolerance at x (NaN where the problem has none).
  double excess_over_tolerance = std::numeric_limits<double>::quiet_NaN();
  ReportedPoint reported = ReportedPoint::CheapestFeasible;
  /// The algorithm's final point, as it says (empty where it does not).
  Eigen::VectorXd final_point;
  /// The cheapest feasible iterate and its own cost (empty and NaN where none is feasible):
  /// x itself unless the reported point is the converged one.
  Eigen::VectorXd cheapest_x;
  double cheapest_cost = std::numeric_limits<double>::quiet_NaN();
  /// The first-order conditions at x where they were checked (a run whose own test passed at x): the
  /// residual and, where the run converged, the multipliers, what relaxing each constraint and bound
  /// is worth in f.
  std::optional<FirstOrderCheck> first_order;
  int iterations = 0;
  long value_evaluations = 0;
  long gradient_evaluations = 0;
  double simulation_equivalents = 0.0;  ///< the budget spent (Budget::simulation_equivalents)
  double wall_time_s = 0.0;  ///< filled by minimize(), around whichever adapter runs
  std::vector<IterationRecord> history;
};

/// One optimizer in the registry (optimizer.cpp): everything the rest of mbsopt knows of it by name.
struct OptimizerInfo {
  std::string name;         ///< what --optimizer, the records and the Python module call it
  std::string description;  ///< one sentence, for --help and the docs
  /// Whether it takes equality constraints; minimize() reports a problem with equalities as
  /// OptimizerStatus::Unsupported for one that does not, before anything is evaluated.
  bool takes_equalities = true;
  /// Whether its runs in one process take turns (Ipopt: its linear solver MUMPS is not thread-safe).
  bool runs_one_at_a_time = false;
  /// Whether `compare` and `benchmark` run it when no --optimizers is given (the set the suite's
  /// published results hold).
  bool compared_by_default = true;
  OptimizerResult (*run)(NlpProblem& problem, const OptimizerOptions& options) = nullptr;
};

/// The registered optimizers, in the order of the tables: sdcc, slsqp, mma, ccsaq, ipopt, auglag_lbfgs.
const std::vector<OptimizerInfo>& optimizers();
/// The registered optimizer `name`; std::invalid_argument listing the names otherwise.
const OptimizerInfo& optimizerInfo(const std::string& name);
/// Every registered name.
std::vector<std::string> optimizerNames();
/// The names with OptimizerInfo::compared_by_default.
std::vector<std::string> defaultComparisonOptimizers();

/// Runs the named optimizer; throws std::invalid_argument for an unknown name.
OptimizerResult minimize(const std::string& optimizer, NlpProblem& problem, const OptimizerOptions& options);

}  // namespace mbsopt
