// The sweep of `mbsopt benchmark`: problems × starts × optimizers × gradient methods × formulations,
// each run a self-describing JSON file under the output directory, the same files whichever way the
// runs are spread (threads here, ranks of an MPI job): a run depends only on its problem, its start
// and its choice, and every gradient it counts costs what the sweep measured once for its problem.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/design/optimization_run.hpp"
#include "mbsopt/design/run_record.hpp"

namespace mbsopt {

struct BenchmarkOptions {
  /// Built-in scene names, design files, or directories (every *.yaml in them, in name order).
  std::vector<std::string> problems;
  SweepAxes axes;
  /// Start 0 is each problem's own; starts 1 … starts − 1 a Latin hypercube in its bounds.
  int starts = 5;
  std::uint64_t seed = 1;
  RunChoice shared;  ///< ε, budget, iteration limit and settings of every run
  std::string out;
  int jobs = 1;  ///< runs at once on this machine (each rank's, under MPI)
};

/// One problem of the sweep, loaded, with its starts (SI design values, start 0 its own).
struct BenchmarkProblem {
  std::string argument;  ///< as given: a built-in name or a file
  std::string name;      ///< the file's stem, or the built-in name: the runs' directory
  std::string path;      ///< the scene's path as its runs record it
  DesignProblem problem;
  std::vector<std::vector<double>> starts;
};

struct BenchmarkRun {
  std::size_t problem = 0;  ///< into the problems
  int start = 0;
  RunChoice choice;         ///< resolved (resolvedChoice), its gradient_cost the sweep's
  /// The solver the report compares: runLabel of the choice as the sweep names it, before it is
  /// resolved ("sdcc/adjoint/problem's formulation" for each problem's own).
  std::string solver;
  std::string file;         ///< relative to the output directory: runs/NAME/STEM-sK.json
};

struct BenchmarkPlan {
  std::vector<BenchmarkProblem> problems;
  std::vector<BenchmarkRun> runs;
};

/// Loads the problems, draws their starts (latinHypercube with the options' seed, in the design
/// variables' bounds) and lists the runs, problems outermost, then starts, formulations, gradients,
/// optimizers. Gradient costs are left empty (measureSweepGradientCosts).
BenchmarkPlan benchmarkPlan(const BenchmarkOptions& options);

/// Every exact gradient method's cost on every problem of the plan, in simulation-equivalents,
/// {NAME: {METHOD: cost}}: read from OUT/gradient_costs.json where an earlier (interrupted) sweep
/// measured it, else measured at the problem's start (measureGradientCosts), alone on the
/// machine, and written there, so that a resumed sweep counts as the first one did.
nlohmann::json sweepGradientCosts(const BenchmarkOptions& options, const BenchmarkPlan& plan);
/// Sets each run's gradient_cost from those costs (finite differences count their own).
void setGradientCosts(const nlohmann::json& costs, BenchmarkPlan& plan);

/// Whether OUT/FILE holds a finished run (a JSON object with a status): a resumed sweep skips it.
bool runFinished(const std::string& out, const BenchmarkRun& run);

/// Runs one run of the plan: its problem at its start with its choice. The record is toJson's with a
/// "benchmark" object (problem, start, start_kind, seed, starts, file); a run that cannot even
/// start (a start the model refuses) is recorded with status "error" and the reason.
nlohmann::json executeRun(const BenchmarkOptions& options, const BenchmarkPlan& plan, const BenchmarkRun& run,
                          std::shared_ptr<ThreadBudget> shared_threads = nullptr);

/// The fields of a run record that depend on the machine, its load or how the program was launched
/// (wall times, timed figures, simulations run ahead on idle cores, the command line): everything
/// else is the same whichever way the sweep ran.
const std::vector<std::string>& machineDependentFields();

}  // namespace mbsopt
