#include "app/benchmark_command.hpp"

#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>

#include "mbsopt/sensitivity/parallel_runs.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/design/benchmark_plan.hpp"
#include "mbsopt/design/benchmark_report.hpp"
#include "app/mpi_sweep.hpp"
#include "app/optimization_options.hpp"
#include "app/option_checks.hpp"
#include "app/output_paths.hpp"

namespace mbsopt {

namespace {

/// One line per finished run.
void printRun(std::size_t done, std::size_t count, const BenchmarkRun& run, const nlohmann::json& record) {
  const std::string status = record["status"];
  std::printf("[%zu/%zu] %s: %s", done, count, run.file.c_str(), status.c_str());
  if (record.contains("cost_functional"))
    std::printf(", %s %.8g, %s, %.0f simulation-equivalents, %.1f s",
                record["cost_functional"]["name"].get<std::string>().c_str(),
                record["cost_functional"]["final"].get<double>(), record["feasible"].get<bool>() ? "feasible" : "NOT feasible",
                record["simulation_equivalents"].get<double>(), record["wall_time_s"].get<double>());
  std::printf("\n");
  std::fflush(stdout);
}

void benchmark(const BenchmarkOptions& options) {
  std::optional<MpiSweep> mpi;
  if (launchedByMpi()) mpi.emplace();
  const bool root = !mpi || mpi->rank() == 0;
  BenchmarkPlan plan = benchmarkPlan(options);
  std::string costs;
  if (root) {
    checkOutputDirectory("--out", options.out);
    costs = sweepGradientCosts(options, plan).dump();
  }
  if (mpi) costs = mpi->broadcast(costs);
  setGradientCosts(nlohmann::json::parse(costs), plan);
  // The runs left: all but those an earlier sweep finished; Ipopt's first (over MPI each rank is a
  // process of its own, and the longest runs are best started first).
  std::vector<std::size_t> todo;
  if (root)
    for (std::size_t i = 0; i < plan.runs.size(); ++i)
      if (!runFinished(options.out, plan.runs[i])) todo.push_back(i);
  std::stable_partition(todo.begin(), todo.end(), [&](std::size_t i) { return optimizerInfo(plan.runs[i].choice.optimizer).runs_one_at_a_time; });
  if (root)
    std::printf("benchmark: %zu problems, %zu runs, %zu finished before, %zu to run %s\n", plan.problems.size(),
                plan.runs.size(), plan.runs.size() - todo.size(), todo.size(),
                mpi && mpi->size() > 1
                    ? ("on " + std::to_string(mpi->size() - 1) + (mpi->size() > 2 ? " worker ranks" : " worker rank") + " (MPI)").c_str()
                    : ("on " + std::to_string(options.jobs) + " threads").c_str());
  std::size_t done = 0;
  const auto store = [&](std::size_t i, const nlohmann::json& record) {
    const std::string path = options.out + "/" + plan.runs[i].file;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    writeAtomically(path, [&](std::ostream& out) { out << record.dump(2) << '\n'; });
    printRun(++done, todo.size(), plan.runs[i], record);
  };
  if (mpi && mpi->size() > 1) {
    BenchmarkOptions rank_options = options;
    rank_options.jobs = 1;  // a rank per core: each run's gradients on its own
    mpi->distribute(
        todo, [&](std::size_t i) { return executeRun(rank_options, plan, plan.runs[i]).dump(); },
        [&](std::size_t i, const std::string& text) { store(i, nlohmann::json::parse(text)); });
  } else {
    // As `mbsopt compare`: each run on its own thread, the idle ones lent to the gradients of the
    // runs still going; the records do not depend on --jobs. Runs that take turns in a process
    // (Ipopt's) go to one thread at a time: a thread takes one when none is running, else any other
    // run, and only when nothing else is left waits for its turn.
    const auto idle_threads = std::make_shared<ThreadBudget>();
    std::mutex lock_queue, output;
    std::deque<std::size_t> in_turn, free_runs;
    for (const std::size_t i : todo) (optimizerInfo(plan.runs[i].choice.optimizer).runs_one_at_a_time ? in_turn : free_runs).push_back(i);
    int turns_running = 0;
    runInParallel(todo.size(), options.jobs, [&](std::size_t) {
      std::size_t i = 0;
      bool takes_turn = false;
      {
        const std::scoped_lock lock(lock_queue);
        takes_turn = !in_turn.empty() && (turns_running == 0 || free_runs.empty());
        std::deque<std::size_t>& queue = takes_turn ? in_turn : free_runs;
        i = queue.front();
        queue.pop_front();
        turns_running += takes_turn;
      }
      const nlohmann::json record = executeRun(options, plan, plan.runs[i], idle_threads);
      {
        const std::scoped_lock lock(lock_queue);
        turns_running -= takes_turn;
      }
      const std::scoped_lock lock(output);
      store(i, record);
    }, idle_threads.get());
  }
  if (!root) return;
  const std::string report = writeBenchmarkReport(options, plan);
  std::printf("\n%s", report.substr(0, report.find("\n## ", report.find("## All problems") + 1)).c_str());
  std::printf("\nwrote %s/report.md, summary.csv, profiles.png, convergence/*.png and runs/*/*.json\n", options.out.c_str());
}

}  // namespace

void registerBenchmarkCommand(CLI::App& app) {
  auto options = std::make_shared<BenchmarkOptions>();
  options->jobs = machineThreads();
  options->shared.budget.simulation_equivalents = 500.0;
  options->shared.max_iterations = 100000;
  CLI::App* command = app.add_subcommand(
      "benchmark",
      "Run every optimizer × gradient method × formulation on every problem from several starts, under one budget "
      "for all, and report: tables per problem, the reasons of every run that did not converge, convergence plots, "
      "Dolan–Moré performance and Moré–Wild data profiles (report.md). One JSON per run under OUT/runs/PROBLEM/; a "
      "run whose file exists is not run again, so an interrupted sweep resumes where it stopped. Under MPI "
      "(mpirun -n N mbsopt benchmark …, or srun) rank 0 hands the runs to the N − 1 others as they finish and writes "
      "the same files");
  command->add_option("problems", options->problems,
                      "Design problems: built-in names (tramway), design files, or directories (every .yaml in them: "
                      "problems/suite)")
      ->required();
  addSweepOptions(*command, options->axes, options->shared);
  command->add_option("--starts", options->starts,
                      "Starts per problem: its own, then a Latin hypercube in the design variables' bounds, the same "
                      "for every optimizer")
      ->check(positiveInteger())
      ->capture_default_str();
  command->add_option("--seed", options->seed, "The Latin hypercube's seed")->capture_default_str();
  addBudgetOptions(*command, options->shared);
  command->get_option("--budget")->capture_default_str()->description(
      "The budget of each run in simulation-equivalents, alike for every optimizer: a simulation counts 1, a gradient "
      "its cost (finite differences their simulations; an exact method what the sweep measured once per problem, "
      "OUT/gradient_costs.json)");
  command->get_option("--max-iter")->default_val(100000);
  addSettingOption(*command, options->shared.settings);
  command->add_option("--jobs", options->jobs,
                      "Runs at once on this machine (default: its hardware threads); under MPI each rank runs one at a "
                      "time. The records do not depend on it")
      ->check(positiveInteger())
      ->capture_default_str();
  command->add_option("--out", options->out, "The sweep's directory (created if missing; an existing one is resumed)")
      ->required();
  command->callback([options] { benchmark(*options); });
}

}  // namespace mbsopt
