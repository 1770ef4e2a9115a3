// `mbsopt benchmark` end to end on two problems of the suite, two optimizers and three starts: one
// self-describing record per run; the same starts for every optimizer (start 0 the problem's own,
// the others a Latin hypercube in the bounds); a second call resumes (runs nothing, changes no
// file); the report tabulates every run; and the same sweep over two MPI ranks (mpirun -n 2: rank 0
// hands out, rank 1 runs) writes the same records as the threaded one, but for the fields that
// depend on the machine or the launch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "mbsopt/io/scene_file.hpp"
#include "tests/plot_data.hpp"

namespace mbsopt {
namespace {

namespace fs = std::filesystem;

const fs::path kSuite = fs::path(MBSOPT_SOURCE_DIR) / "problems" / "suite";
const std::vector<std::string> kProblems{"quarter_car", "spring_floor"};
const std::vector<std::string> kOptimizers{"sdcc", "slsqp"};
constexpr int kStarts = 3;

/// The fields of a record that depend on the machine or the launch (benchmark_plan.hpp).
const std::vector<std::string> kMachineDependent{"command_line",      "wall_time_s",           "simulation_s",
                                                 "thread_time_simulations", "simulations_ahead",
                                                 "simulations_ahead_used"};

std::string sweep(const fs::path& out) {
  std::string command = " benchmark";
  for (const std::string& problem : kProblems) {
    command += ' ';
    command += (kSuite / (problem + ".yaml")).string();
  }
  command += " --optimizers sdcc,slsqp --starts 3 --seed 7 --out ";
  return command += out.string();
}

std::string run(const std::string& command, const fs::path& output) {
  EXPECT_EQ(std::system((command + " > " + output.string() + " 2>&1").c_str()), 0) << command;
  std::ifstream in(output);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json record(const fs::path& out, const std::string& problem, const std::string& optimizer, int start) {
  nlohmann::json json;
  std::ifstream(out / "runs" / problem / (optimizer + "-adjoint-grid_max-s" + std::to_string(start) + ".json")) >> json;
  return json;
}

std::vector<double> startOf(const nlohmann::json& run) {
  std::vector<double> start;
  for (const nlohmann::json& v : run["variables"]) start.push_back(v["start"].get<double>());
  return start;
}

TEST(BenchmarkCommand, SweepsResumesAndGivesTheSameRecordsOverMpiRanks) {
  const fs::path directory = fs::temp_directory_path() / ("mbsopt_benchmark_" + std::to_string(::getpid()));
  fs::remove_all(directory);
  fs::create_directories(directory);
  const fs::path threaded = directory / "threaded", ranks = directory / "mpi";
  const std::string executable = MBSOPT_EXECUTABLE;
  const std::string first = run(executable + sweep(threaded) + " --jobs 2", directory / "first.txt");
  EXPECT_NE(first.find("12 runs, 0 finished before, 12 to run"), std::string::npos) << first;

  for (const std::string& problem : kProblems) {
    const DesignProblem loaded = loadDesignProblem(readSceneFile((kSuite / (problem + ".yaml")).string()));
    std::vector<std::vector<double>> starts;
    for (int s = 0; s < kStarts; ++s) {
      const nlohmann::json sdcc = record(threaded, problem, "sdcc", s), slsqp = record(threaded, problem, "slsqp", s);
      ASSERT_TRUE(sdcc.contains("status")) << problem << " start " << s;
      EXPECT_EQ(startOf(sdcc), startOf(slsqp)) << problem << ": every optimizer from the same start";
      EXPECT_EQ(sdcc["benchmark"]["start"], s);
      EXPECT_EQ(sdcc["benchmark"]["seed"], 7);
      EXPECT_EQ(sdcc["benchmark"]["problem"], problem);
      for (const char* field : {"mbsopt_version", "command_line", "variables", "budget", "settings", "epsilon",
                                "constraints", "cost_functional", "history"})
        EXPECT_TRUE(sdcc.contains(field)) << field;
      EXPECT_EQ(sdcc["budget"]["simulation_equivalents"], 500.0);
      starts.push_back(startOf(sdcc));
    }
    // Start 0 is the problem's own; starts 1 and 2 a Latin hypercube of two points: one in each half
    // of every variable's range.
    for (std::size_t i = 0; i < loaded.design.variables.size(); ++i) {
      const DesignVariable& v = loaded.design.variables[i];
      EXPECT_EQ(starts[0][i], loaded.scene.model.parameter(v.parameter));
      const double middle = 0.5 * (v.lower + v.upper);
      EXPECT_TRUE((starts[1][i] < middle) != (starts[2][i] < middle)) << v.parameter;
      for (int s = 1; s < kStarts; ++s) {
        EXPECT_GE(starts[static_cast<std::size_t>(s)][i], v.lower);
        EXPECT_LE(starts[static_cast<std::size_t>(s)][i], v.upper);
      }
    }
  }
  // The report: a row per solver for every problem, and a CSV line per run.
  std::ifstream report_file(threaded / "report.md");
  std::stringstream report;
  report << report_file.rdbuf();
  for (const std::string& problem : kProblems) EXPECT_NE(report.str().find("## " + problem), std::string::npos);
  EXPECT_NE(report.str().find("| sdcc/adjoint/problem's formulation | 6 |"), std::string::npos) << report.str();
  // The CSV gives each run's reported point as its record does, to the bit, with its unit.
  std::ifstream csv(threaded / "summary.csv");
  std::string header_line;
  std::getline(csv, header_line);
  std::vector<std::string> header;
  for (std::stringstream fields(header_line); std::getline(fields, header_line, ',');) header.push_back(header_line);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  int lines = 1;
  for (std::string line; std::getline(csv, line); ++lines) {
    std::vector<std::string> cells;
    for (std::stringstream fields(line); std::getline(fields, line, ',');) cells.push_back(line);
    ASSERT_EQ(cells.size(), header.size());
    const nlohmann::json r = record(threaded, cells[column("problem")], cells[column("optimizer")], std::stoi(cells[column("start")]));
    EXPECT_EQ(cells[column("reported_point")], r["reported_iterate"]["point"]);
    EXPECT_EQ(std::stoi(cells[column("reported_iteration")]), r["reported_iterate"]["iteration"].get<int>());
    EXPECT_EQ(std::stod(cells[column("cost_functional")]), r["cost_functional"]["final"].get<double>());
    EXPECT_EQ(cells[column("cost_unit")], r["cost_functional"]["unit"]);
    // The reported point is a record of the history, whose cost is the one reported.
    bool in_history = false;
    for (const nlohmann::json& h : r["history"])
      if (h["iteration"] == r["reported_iterate"]["iteration"]) {
        in_history = true;
        EXPECT_EQ(h["cost_functional"].get<double>(), r["cost_functional"]["final"].get<double>());
      }
    EXPECT_TRUE(in_history);
  }
  EXPECT_EQ(lines, 1 + 12);
  for (const char* figure : {"profiles.png", "convergence/quarter_car.png", "convergence/spring_floor.png"})
    EXPECT_TRUE(fs::exists(threaded / figure)) << figure;
  // The convergence plots ring the same point: per start, the cost panel's curve of each solver, then
  // its reported point, which is that curve's point at the reported iteration's simulation-equivalents
  // (then the violation panel's curves and marks).
  for (const std::string& problem : kProblems) {
    const std::vector<test::PlotBlock> blocks = test::readPlotBlocks(threaded / "convergence" / (problem + ".dat"));
    ASSERT_EQ(blocks.size(), static_cast<std::size_t>(kStarts) * 4 * kOptimizers.size()) << problem;
    for (int s = 0; s < kStarts; ++s)
      for (std::size_t o = 0; o < kOptimizers.size(); ++o) {
        const std::size_t first = static_cast<std::size_t>(s) * 4 * kOptimizers.size();
        const test::PlotBlock& curve = blocks[first + o];
        const test::PlotBlock& mark = blocks[first + kOptimizers.size() + o];
        ASSERT_EQ(mark.title, "(marks)");
        ASSERT_EQ(mark.points.size(), 1u) << problem << " " << kOptimizers[o] << " start " << s;
        const nlohmann::json r = record(threaded, problem, kOptimizers[o], s);
        for (const nlohmann::json& h : r["history"])
          if (h["iteration"] == r["reported_iterate"]["iteration"]) {
            EXPECT_EQ(mark.points[0].first, h["simulation_equivalents"].get<double>());
          }
        EXPECT_NE(std::find(curve.points.begin(), curve.points.end(), mark.points[0]), curve.points.end())
            << problem << " " << kOptimizers[o] << " start " << s;
      }
  }

  // Resumed: nothing runs again, no record changes.
  const auto written = fs::last_write_time(threaded / "runs" / "quarter_car" / "sdcc-adjoint-grid_max-s1.json");
  const std::string second = run(executable + sweep(threaded), directory / "second.txt");
  EXPECT_NE(second.find("12 runs, 12 finished before, 0 to run"), std::string::npos) << second;
  EXPECT_EQ(fs::last_write_time(threaded / "runs" / "quarter_car" / "sdcc-adjoint-grid_max-s1.json"), written);

  // Over MPI, with the threaded sweep's measured gradient costs (a sweep reads them where an earlier
  // one wrote them): the same records. Open MPI's own allocations outlive MPI_Finalize, which
  // LeakSanitizer would report in the sanitizer build; the threaded sweep above runs the same code
  // of ours with leak detection on.
  fs::create_directories(ranks);
  fs::copy_file(threaded / "gradient_costs.json", ranks / "gradient_costs.json");
  const std::string launch =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ASAN_OPTIONS=detect_leaks=0 "
      "mpirun -n 2 --oversubscribe " + executable;
  const std::string over_mpi = run(launch + sweep(ranks), directory / "mpi.txt");
  EXPECT_NE(over_mpi.find("12 to run on 1 worker rank (MPI)"), std::string::npos) << over_mpi;
  for (const std::string& problem : kProblems)
    for (const std::string& optimizer : kOptimizers)
      for (int s = 0; s < kStarts; ++s) {
        nlohmann::json a = record(threaded, problem, optimizer, s), b = record(ranks, problem, optimizer, s);
        ASSERT_TRUE(b.contains("status")) << problem << " " << optimizer << " start " << s;
        for (const std::string& field : kMachineDependent) {
          EXPECT_TRUE(a.contains(field)) << field;
          a.erase(field);
          b.erase(field);
        }
        EXPECT_EQ(a, b) << problem << " " << optimizer << " start " << s;
      }
  fs::remove_all(directory);
}

}  // namespace
}  // namespace mbsopt
