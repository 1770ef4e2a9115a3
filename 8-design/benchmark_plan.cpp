#include "mbsopt/design/benchmark_plan.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/optimizers/latin_hypercube.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/io/scene_lookup.hpp"

namespace mbsopt {

namespace fs = std::filesystem;

namespace {

/// The arguments with each directory replaced by its *.yaml files, in name order.
std::vector<std::string> problemArguments(const std::vector<std::string>& arguments) {
  std::vector<std::string> out;
  for (const std::string& argument : arguments) {
    if (!fs::is_directory(argument)) {
      out.push_back(argument);
      continue;
    }
    std::vector<std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(argument))
      if (entry.is_regular_file() && entry.path().extension() == ".yaml") files.push_back(entry.path().string());
    if (files.empty()) throw std::invalid_argument("benchmark: the directory " + argument + " holds no .yaml problem");
    std::sort(files.begin(), files.end());
    out.insert(out.end(), files.begin(), files.end());
  }
  return out;
}

/// Start 0, the problem's own, then count − 1 points of a Latin hypercube in the variables' bounds.
std::vector<std::vector<double>> startsOf(const BenchmarkProblem& p, int count, std::uint64_t seed) {
  const std::vector<DesignVariable>& variables = p.problem.design.variables;
  const auto n = static_cast<Eigen::Index>(variables.size());
  Eigen::VectorXd lower(n), upper(n);
  std::vector<double> own;
  for (Eigen::Index i = 0; i < n; ++i) {
    const DesignVariable& v = variables[static_cast<std::size_t>(i)];
    if (!std::isfinite(v.lower) || !std::isfinite(v.upper))
      throw std::invalid_argument("benchmark: " + p.name + "'s variable " + v.parameter +
                                  " has no finite bounds, and the starts are drawn in them");
    lower[i] = v.lower;
    upper[i] = v.upper;
    own.push_back(p.problem.scene.model.value(v.index));
  }
  std::vector<std::vector<double>> starts{own};
  for (const Eigen::VectorXd& x : latinHypercube(lower, upper, count - 1, seed))
    starts.emplace_back(x.data(), x.data() + x.size());
  return starts;
}

bool costIsMeasured(const std::string& gradient) { return gradientMethod(gradient).simulations_per_variable == 0; }

}  // namespace

BenchmarkPlan benchmarkPlan(const BenchmarkOptions& options) {
  if (options.starts < 1) throw std::invalid_argument("benchmark: --starts must be at least 1");
  BenchmarkPlan plan;
  for (const std::string& argument : problemArguments(options.problems)) {
    const SceneSource source = resolveScene(argument);
    BenchmarkProblem p{argument, fs::path(argument).stem().string(), source.path, loadDesignProblem(source), {}};
    for (const BenchmarkProblem& other : plan.problems)
      if (other.name == p.name) throw std::invalid_argument("benchmark: two problems named " + p.name);
    p.starts = startsOf(p, options.starts, options.seed);
    plan.problems.push_back(std::move(p));
  }
  for (std::size_t i = 0; i < plan.problems.size(); ++i)
    for (int start = 0; start < options.starts; ++start)
      for (const RunChoice& unresolved : sweepChoices(options.axes, options.shared)) {
        const RunChoice choice = resolvedChoice(plan.problems[i].problem, unresolved);
        const std::string file =
            "runs/" + plan.problems[i].name + "/" + runFileStem(choice) + "-s" + std::to_string(start) + ".json";
        plan.runs.push_back({i, start, choice, runLabel(unresolved), file});
      }
  return plan;
}

nlohmann::json sweepGradientCosts(const BenchmarkOptions& options, const BenchmarkPlan& plan) {
  const std::string path = options.out + "/gradient_costs.json";
  nlohmann::json costs = nlohmann::json::object();
  if (std::ifstream in(path); in) costs = nlohmann::json::parse(in, nullptr, false);
  if (!costs.is_object()) throw std::runtime_error(path + ": not the JSON object an earlier sweep wrote");
  bool measured = false;
  for (std::size_t i = 0; i < plan.problems.size(); ++i) {
    const BenchmarkProblem& p = plan.problems[i];
    // This problem's runs of an exact method whose cost is neither given nor in the file.
    std::vector<RunChoice> pending;
    for (const BenchmarkRun& run : plan.runs)
      if (run.problem == i && !run.choice.gradient_cost && costIsMeasured(run.choice.gradient) &&
          !(costs.contains(p.name) && costs[p.name].contains(run.choice.gradient)))
        pending.push_back(run.choice);
    measureGradientCosts(p.problem, pending);  // once per method; none where the start cannot be simulated
    for (const RunChoice& choice : pending)
      if (choice.gradient_cost) {
        costs[p.name][choice.gradient] = *choice.gradient_cost;
        measured = true;
      }
  }
  if (measured) writeAtomically(path, [&](std::ostream& out) { out << costs.dump(2) << '\n'; });
  return costs;
}

void setGradientCosts(const nlohmann::json& costs, BenchmarkPlan& plan) {
  for (BenchmarkRun& run : plan.runs) {
    const std::string& name = plan.problems[run.problem].name;
    if (!run.choice.gradient_cost && costs.contains(name) && costs[name].contains(run.choice.gradient))
      run.choice.gradient_cost = costs[name][run.choice.gradient].get<double>();
  }
}

bool runFinished(const std::string& out, const BenchmarkRun& run) {
  std::ifstream in(out + "/" + run.file);
  if (!in) return false;
  const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
  return record.is_object() && record.contains("status");
}

nlohmann::json executeRun(const BenchmarkOptions& options, const BenchmarkPlan& plan, const BenchmarkRun& run,
                          std::shared_ptr<ThreadBudget> shared_threads) {
  const BenchmarkProblem& p = plan.problems[run.problem];
  const nlohmann::json benchmark = {{"problem", p.name},
                                    {"start", run.start},
                                    {"start_kind", run.start == 0 ? "the problem's own" : "latin_hypercube"},
                                    {"seed", options.seed},
                                    {"starts", options.starts},
                                    {"file", run.file}};
  RunChoice choice = run.choice;
  choice.gradient_jobs = options.jobs;
  try {
    DesignProblem problem = p.problem;
    const std::vector<double>& start = p.starts[static_cast<std::size_t>(run.start)];
    for (std::size_t i = 0; i < start.size(); ++i) problem.scene.model.setParameter(problem.design.variables[i].index, start[i]);
    nlohmann::json record = toJson(runOptimization(std::move(problem), choice, {}, std::move(shared_threads)), p.path);
    record["benchmark"] = benchmark;
    return record;
  } catch (const std::exception& e) {
    return {{"problem", p.path},      {"benchmark", benchmark},      {"optimizer", choice.optimizer},
            {"gradient", choice.gradient}, {"formulation", choice.formulation}, {"status", "error"},
            {"message", e.what()},    {"feasible", false}};
  }
}

const std::vector<std::string>& machineDependentFields() {
  static const std::vector<std::string> fields{"command_line", "wall_time_s",       "simulation_s",
                                               "thread_time_simulations", "simulations_ahead",
                                               "simulations_ahead_used"};
  return fields;
}

}  // namespace mbsopt
