#include "app/compare_command.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <numeric>
#include <sstream>

#include "mbsopt/sensitivity/parallel_runs.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/gnuplot.hpp"
#include "mbsopt/design/optimization_plots.hpp"
#include "mbsopt/design/optimization_run.hpp"
#include "mbsopt/design/run_record.hpp"
#include "app/optimization_options.hpp"
#include "app/option_checks.hpp"
#include "app/output_paths.hpp"
#include "app/scene_argument.hpp"

namespace mbsopt {

namespace {

struct CompareOptions {
  SceneArgument problem;
  SweepAxes axes;
  /// What every run shares: ε of the formulations (empty: the problem's own), the budget and the
  /// iteration limit, the settings (passed to every optimizer that takes them).
  RunChoice shared;
  std::string out;
  int jobs = machineThreads();  ///< runs at once
};


/// One column of the table: its header (with its unit), the value as the Markdown table shows it
/// (rounded) and as the CSV holds it (a number at full precision, or a word).
struct Cell {
  std::string header, shown, exact;
};

/// The table's columns for one run; the same for Markdown and CSV.
std::vector<Cell> row(const OptimizationRun& run, const std::string& cost_key) {
  const OptimizerResult& r = run.result;
  const double final_cost = run.responses[cost_key].get<double>();
  const auto text = [](double value, const char* format) {
    char out[64];
    std::snprintf(out, sizeof out, format, value);
    return std::string(out);
  };
  const auto number = [&](const std::string& header, double value, const char* format) {
    return Cell{header, text(value, format), text(value, "%.17g")};
  };
  const auto word = [](const std::string& header, const std::string& value) { return Cell{header, value, value}; };
  const auto unit = [&](const std::string& key) { return " [" + run.response_units.value(key, std::string("SI")) + "]"; };
  std::vector<Cell> cells{word("optimizer", run.choice.optimizer), word("gradient", run.choice.gradient),
                          word("formulation", formulationLabel(run.choice)), word("status", toString(r.status)),
                          word("reported point", reportedPointName(r)),
                          number(cost_key + unit(cost_key), final_cost, "%.8g"),
                          number("lowered by [%]", 100.0 * (run.initial_cost - final_cost) / run.initial_cost, "%.2f")};
  for (const auto& [name, value] : run.responses.items())
    if (name != cost_key) cells.push_back(number(name + unit(name), value.get<double>(), "%.6g"));
  cells.insert(cells.end(), {word("feasible", feasible(run) ? "yes" : "no"),
                             number("max violation [formulation's measure]", r.max_violation, "%.2g"),
                             word("iterations", std::to_string(r.iterations)),
                             word("simulations", std::to_string(r.value_evaluations)),
                             word("gradients", std::to_string(r.gradient_evaluations)),
                             number("sim.-equivalents", r.simulation_equivalents, "%.0f"),
                             number("wall time [s]", r.wall_time_s, "%.1f")});
  return cells;
}

std::string markdownTable(const std::vector<OptimizationRun>& runs, const std::string& cost_key) {
  std::ostringstream out;
  const auto header = row(runs.front(), cost_key);
  out << '|';
  for (const Cell& cell : header) out << ' ' << cell.header << " |";
  out << "\n|";
  for (std::size_t i = 0; i < header.size(); ++i) out << "---|";
  out << '\n';
  for (const OptimizationRun& run : runs) {
    out << '|';
    for (const Cell& cell : row(run, cost_key)) out << ' ' << cell.shown << " |";
    out << '\n';
  }
  return out.str();
}

/// A CSV field: quoted where it holds a comma or a quote.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csvTable(const std::vector<OptimizationRun>& runs, const std::string& cost_key) {
  std::ostringstream out;
  const auto header = row(runs.front(), cost_key);
  for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << csvField(header[i].header);
  out << '\n';
  for (const OptimizationRun& run : runs) {
    const auto cells = row(run, cost_key);
    for (std::size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << csvField(cells[i].exact);
    out << '\n';
  }
  return out.str();
}

/// The cost's distance to the best and the max violation against simulation-equivalents
/// (convergencePanels): one row of two panels per (formulation, gradient), one curve per optimizer,
/// in the same colour in every row.
void plotConvergence(const std::string& stem, const std::string& problem, const std::vector<OptimizationRun>& runs) {
  std::vector<PlotPanel> panels;
  for (std::size_t first = 0; first < runs.size();) {
    const std::string group = formulationLabel(runs[first].choice) + ", " + runs[first].choice.gradient;
    std::vector<std::pair<std::string, const OptimizationRun*>> titled;
    for (; first < runs.size() && formulationLabel(runs[first].choice) + ", " + runs[first].choice.gradient == group; ++first)
      titled.emplace_back(runs[first].choice.optimizer, &runs[first]);
    std::vector<PlotPanel> row = convergencePanels(titled, true);
    for (PlotPanel& panel : row) panel.title = panel.title.empty() ? group : group + ": " + panel.title;
    panels.insert(panels.end(), row.begin(), row.end());
  }
  plotPanels(stem, "convergence on " + problem, panels, 2);
}

void compare(const CompareOptions& options) {
  checkOutputDirectory("--out", options.out);
  const SceneSource source = resolveScene(options.problem.scene);
  const DesignProblem problem = loadDesignProblem(source, parseOverrides(source, options.problem.sets));
  std::vector<RunChoice> choices = sweepChoices(options.axes, options.shared);
  // Each gradient method's cost measured once, before the runs and alone on the machine, so that
  // every optimizer's budget counts its gradients alike.
  measureGradientCosts(problem, choices);
  // Each run on its own copy of the problem (its own model and workspaces): the runs are
  // independent, and their results do not depend on --jobs. A thread with no run left to start lends
  // itself to the gradients of those still going. The runs that take turns (Ipopt) start first:
  // one after another, they are the longest chain. A line per run as it finishes.
  for (RunChoice& choice : choices) choice.gradient_jobs = options.jobs;
  std::vector<std::size_t> order(choices.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) { return optimizerInfo(choices[i].optimizer).runs_one_at_a_time; });
  const auto idle_threads = std::make_shared<ThreadBudget>();
  std::vector<OptimizationRun> runs(choices.size());
  std::mutex output;
  runInParallel(order.size(), options.jobs, [&](std::size_t k) {
    const std::size_t i = order[k];
    runs[i] = runOptimization(problem, choices[i], {}, idle_threads);
    const OptimizerResult& r = runs[i].result;
    if (!options.out.empty())
      writeAtomically(options.out + "/" + runFileStem(runs[i].choice) + ".json",
                      [&](std::ostream& out) { out << toJson(runs[i], source.path).dump(2) << '\n'; });
    const std::scoped_lock lock(output);
    std::printf("%-40s %-14s cost %-12.6g violation %-9.2g %4ld simulations %7.1f s\n", runLabel(choices[i]).c_str(),
                toString(r.status).c_str(), r.cost, r.max_violation, r.value_evaluations, r.wall_time_s);
    std::fflush(stdout);
  }, idle_threads.get());
  const std::string& cost_key = runs.front().cost_response;
  const std::string table = markdownTable(runs, cost_key);
  std::printf("\n%s", table.c_str());
  if (options.out.empty()) return;
  writeAtomically(options.out + "/comparison.md", [&](std::ostream& out) { out << table; });
  writeAtomically(options.out + "/comparison.csv", [&](std::ostream& out) { out << csvTable(runs, cost_key); });
  plotConvergence(options.out + "/convergence", source.path, runs);
  std::printf("wrote %s/comparison.md, comparison.csv, convergence.png and one JSON per run\n", options.out.c_str());
}

}  // namespace

void registerCompareCommand(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* command = app.add_subcommand(
      "compare",
      "Run every combination of optimizers, gradient methods and formulations on one design problem from its start "
      "and tabulate them: status, final cost (the cost sensor's max |y|) and how much it fell, max violation, "
      "iterations, simulations, gradients, simulation-equivalents (the budget's count: simulations plus gradients at "
      "their cost), wall time");
  addSceneArgument(*command, options->problem, true);
  addSweepOptions(*command, options->axes, options->shared);
  addBudgetOptions(*command, options->shared);
  addSettingOption(*command, options->shared.settings);
  command->add_option("--jobs", options->jobs,
                      "Threads (default: this machine's hardware threads): runs at once, each on its own thread, and "
                      "when no run is left to start, the idle threads help the gradients of the runs still going. Ipopt "
                      "runs one at a time (its linear solver MUMPS is not thread-safe) and starts first; the results "
                      "do not depend on --jobs")
      ->check(positiveInteger())
      ->capture_default_str();
  command->add_option("--out", options->out,
                      "Directory for comparison.md, comparison.csv, convergence.png (with its .dat and .gp) and one "
                      "JSON per run (created if missing)");
  command->callback([options] { locatingRunFailures(options->problem, [&] { compare(*options); }); });
}

}  // namespace mbsopt
