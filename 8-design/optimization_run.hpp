// One optimizer run on a design problem, as `mbsopt optimize` and `mbsopt compare` perform it: the
// problem with the chosen formulation, the gradients of the chosen method, the result, the final
// design in SI units and its responses. run_record.hpp writes it as JSON.
#pragma once

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/sensitivity/formulation.hpp"
#include "mbsopt/sensitivity/thread_budget.hpp"
#include "mbsopt/optimizers/optimizer.hpp"
#include "mbsopt/design/bound_worth.hpp"
#include "mbsopt/design/constraint_verdicts.hpp"

namespace mbsopt {

struct RunChoice {
  std::string optimizer = "sdcc";
  std::string gradient = "adjoint";  ///< a gradientMethodChoices() entry
  /// positive_part | squared_positive_part | ks | grid_max; empty: the problem's own measure, as
  /// its scene file or C++ description says.
  std::string formulation;
  /// ε of the transcription (each measure ≤ ε); empty: the problem's own. After a run: the ε it used.
  std::optional<double> epsilon;
  int max_iterations = 100;  ///< each optimizer's own count (OptimizerOptions::max_iterations)
  Budget budget;             ///< the common budget (simulation-equivalents, wall time), alike for every optimizer
  /// What one gradient costs in simulation-equivalents (the budget's unit); empty: counted for finite
  /// differences, measured at the start for an exact method (DesignNlp::measureGradientCost).
  std::optional<double> gradient_cost;
  std::vector<std::string> settings;  ///< the optimizer's own settings, "NAME=VALUE" each
  /// The most threads a gradient takes (designGradient's jobs; no effect on results): its own, or
  /// with runOptimization's shared_threads, those idle at the time.
  int gradient_jobs = 1;
};

/// The reported point's name as the outputs give it: toString(ReportedPoint), or "start" for a run
/// whose optimizer cannot take the problem (it evaluated nothing; the start is what it reports).
std::string reportedPointName(const OptimizerResult& result);

struct OptimizationRun {
  RunChoice choice;
  OptimizerResult result;
  std::vector<DesignVariable> variables;  ///< the design variables: parameter names, bounds and scales (SI)
  std::vector<std::string> variable_units;  ///< each one's SI unit (parameterUnit; "" where it has none)
  ArtificialVariable artificial;         ///< b_{k+1}'s start, bounds and scale
  std::vector<double> start;  ///< the design variables at the start in SI units, without b_{k+1}
  /// The history's record of the reported point (result.x, OptimizerResult::reported says which), or
  /// −1 where no record holds it.
  int reported_iteration = -1;
  /// Where the reported point is the converged one: the cheapest feasible iterate, its own cost
  /// (cost_response's unit) and its record (−1: none holds it), when it is another point; NaN and −1
  /// otherwise.
  double cheapest_cost = std::numeric_limits<double>::quiet_NaN();
  int cheapest_iteration = -1;
  /// Where the optimizer's multipliers are known at the reported point (a converged run): what
  /// relaxing each active bound is worth (bound_worth.hpp), and what the constraints' tolerances are
  /// worth together (toleranceWorth; NaN without multipliers).
  std::vector<BoundWorth> bound_worth;
  double tolerance_worth = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> design;  ///< the final design variables in SI units, without b_{k+1}
  /// The design (SI, without b_{k+1}) at each record of result.history; empty where the optimizer
  /// did not say which point an iteration was.
  std::vector<std::vector<double>> iterate_designs;
  /// The cost's own functional (cost_response's unit) at each record of result.history; NaN where
  /// the optimizer did not say which point an iteration was.
  std::vector<double> iterate_costs;
  /// The gradient cost the budget counted with (RunChoice::gradient_cost), and where it came from:
  /// "given", "counted" (finite differences) or "measured".
  double gradient_cost = 1.0;
  std::string gradient_cost_source;
  /// max |y| of each sensor of the cost and constraints (`max_abs_NAME`), and the value of each exact
  /// functional the cost or a constraint takes (`integral_NAME`, `rms_NAME`, `final_NAME`); angles in degrees.
  nlohmann::json responses;
  nlohmann::json response_units;  ///< the unit of each of `responses`, by the same keys
  std::string cost_response;   ///< the key in `responses` of the cost's own functional (max_abs_, rms_, integral_)
  /// Every constraint judged at the final design in its own units, whatever the formulation.
  std::vector<ConstraintVerdict> verdicts;
  std::string cost_sensor;     ///< the cost's sensor
  std::string cost_unit;       ///< the unit of cost_response (sensorUnit; ·s for an integral)
  std::string cost_sensor_unit;  ///< the SI unit of the cost's sensor (initial_history, final_history)
  double initial_cost = 0.0;   ///< the cost's functional (cost_response) at the start
  double simulation_s = 0.0;   ///< the wall time of one simulation of this problem (the fastest the run timed)
  /// The optimizer's evaluations (simulations and gradients) in simulations as timed: their thread
  /// time (DesignNlp::evaluationThreadSeconds: each one's wall time times the threads it held) over
  /// simulation_s, so that runs with different numbers of threads compare. The budget's count is
  /// result.simulation_equivalents.
  double thread_time_simulations = 0.0;
  /// Simulations run ahead on a spare core for a point the optimizer might ask next (SDCC's trial
  /// after a rejection, DesignNlp::anticipate), and how many of them it did ask for (those are
  /// among result.value_evaluations; the others only kept an idle core busy).
  long simulations_ahead = 0, simulations_ahead_used = 0;
  /// The cost's sensor over time (SI) at the start and at the final design (the paper's figure 8).
  Eigen::VectorXd time, initial_history, final_history;
};

/// Whether the final design meets every constraint in its own units (ConstraintVerdict::met).
inline bool feasible(const OptimizationRun& run) {
  return std::all_of(run.verdicts.begin(), run.verdicts.end(), [](const ConstraintVerdict& v) { return v.met(); });
}

/// The combinations a sweep runs (`mbsopt compare`, `mbsopt benchmark`): formulations outermost,
/// then gradient methods, then optimizers.
struct SweepAxes {
  std::vector<std::string> optimizers = defaultComparisonOptimizers();
  std::vector<std::string> gradients{"adjoint"};
  std::vector<std::string> formulations{""};  ///< "": the problem's own
};

/// Every combination of the axes, in their order, each `shared` with its optimizer, gradient and formulation.
std::vector<RunChoice> sweepChoices(const SweepAxes& axes, const RunChoice& shared);

/// The formulation with its ε where ε > 0: "positive_part", "positive_part ε=1e-06"
/// ("problem's formulation" before resolvedChoice).
std::string formulationLabel(const RunChoice& choice);
/// OPTIMIZER/GRADIENT/formulationLabel.
std::string runLabel(const RunChoice& choice);

/// The choice as it runs on `problem`: the problem's own formulation and ε where the choice names
/// none, "fd" as fd_central. Throws std::invalid_argument for an unknown formulation.
RunChoice resolvedChoice(const DesignProblem& problem, RunChoice choice);

/// A resolved choice's file name without extension: OPTIMIZER-GRADIENT-FORMULATION[-epsE].
std::string runFileStem(const RunChoice& choice);

/// The problem with the transcription of a resolved choice (its formulation's measure and its ε).
DesignProblem formulatedProblem(DesignProblem problem, const RunChoice& resolved);

/// Runs `choice` on `problem` (its transcription replaced by the choice's formulation). With
/// `shared_threads`, the threads its evaluations use beyond their own are borrowed from it while idle
/// (runs at once lend theirs to one another; thread_budget.hpp). A limit or number of the choice out
/// of its range (max_iterations < 1, a budget ≤ 0 or NaN, a negative or non-finite ε, ...) is an
/// std::invalid_argument that names it, before anything runs.
OptimizationRun runOptimization(DesignProblem problem, const RunChoice& choice,
                                const std::function<void(const IterationRecord&)>& on_iteration,
                                std::shared_ptr<ThreadBudget> shared_threads = nullptr);

/// Sets the gradient_cost of every choice that has none and takes an exact method: measured once per
/// gradient method at the problem's start (DesignNlp::measureGradientCost), so that runs going on
/// at once, whose timings would disturb one another, count their gradients alike.
void measureGradientCosts(const DesignProblem& problem, std::vector<RunChoice>& choices);

}  // namespace mbsopt
