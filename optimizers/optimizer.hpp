// One interface over every optimizer (docs/design.md §5): minimize(name, problem, options) returns the
// same record whichever algorithm ran, with a per-iteration history, and counts evaluations the way
// the design problems pay for them (value evaluations = simulations, gradient evaluations).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>
#include <vector>

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
  Eigen::VectorXd x;    ///< the best point found (feasible first, then lowest cost)
  double cost = 0.0;
  double max_violation = 0.0;
  int iterations = 0;
  long value_evaluations = 0;
  long gradient_evaluations = 0;
  double simulation_equivalents = 0.0;  ///< the budget spent (Budget::simulation_equivalents)
  double wall_time_s = 0.0;  ///< filled by minimize(), around whichever adapter runs
  std::vector<IterationRecord> history;
};

/// The optimizers by name: "sdcc", "slsqp", "mma", "ccsaq", "ipopt".
const std::vector<std::string>& optimizerNames();

/// Whether the named optimizer's runs in one process take turns (Ipopt: its linear solver MUMPS is
/// not thread-safe, so minimize() runs one Ipopt at a time).
bool runsOneAtATime(const std::string& optimizer);

/// Runs the named optimizer; throws std::invalid_argument for an unknown name.
OptimizerResult minimize(const std::string& optimizer, NlpProblem& problem, const OptimizerOptions& options);

}  // namespace mbsopt
