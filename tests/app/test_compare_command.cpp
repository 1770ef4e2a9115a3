// `mbsopt compare` end to end on the open chain: one table row and one JSON per combination, the
// table's figures the same as the JSON's, a setting meant for one optimizer given to it alone, and a
// convergence plot with one block per run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "tests/plot_data.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

TEST(CompareCommand, WritesOneRowAndOneJsonPerCombinationThatAgree) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("mbsopt_compare_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  const std::filesystem::path scene = directory / "chain.yaml", out = directory / "out";
  std::ofstream(scene) << test::kOpenChainProblem;
  const std::string command = std::string(MBSOPT_EXECUTABLE) + " compare " + scene.string() +
                              " --optimizers sdcc,slsqp --formulations ks,grid_max --max-iter 8"
                              " --setting sdcc.initial_step_bound=0.05 --out " +
                              out.string() + " > " + (directory / "stdout").string();
  ASSERT_EQ(std::system(command.c_str()), 0);

  std::ifstream csv(out / "comparison.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const std::vector<std::string> header = splitCsv(line);
  const auto column = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    EXPECT_NE(at, header.end()) << name;
    return static_cast<std::size_t>(at - header.begin());
  };
  for (const char* name : {"optimizer", "gradient", "formulation", "status", "reported point", "feasible",
                           "max violation [formulation's measure]", "iterations", "simulations", "gradients",
                           "sim.-equivalents", "wall time [s]", "lowered by [%]"})
    column(name);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) rows.push_back(splitCsv(line));
  ASSERT_EQ(rows.size(), 4u);  // (ks, grid_max) × (sdcc, slsqp), formulations outermost
  const std::vector<std::pair<std::string, std::string>> expected{
      {"sdcc", "ks"}, {"slsqp", "ks"}, {"sdcc", "grid_max"}, {"slsqp", "grid_max"}};
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto& [optimizer, formulation] = expected[r];
    EXPECT_EQ(rows[r][column("optimizer")], optimizer);
    EXPECT_EQ(rows[r][column("formulation")], formulation);
    nlohmann::json run;
    std::ifstream(out / (optimizer + "-adjoint-" + formulation + ".json")) >> run;
    EXPECT_EQ(rows[r][column("status")], run["status"].get<std::string>());
    EXPECT_EQ(std::stol(rows[r][column("simulations")]), run["simulations"].get<long>());
    EXPECT_EQ(std::stol(rows[r][column("iterations")]), run["iterations"].get<long>());
    EXPECT_EQ(rows[r][column("feasible")], run["feasible"].get<bool>() ? "yes" : "no");
    // The budget's count: a simulation 1, a gradient its cost, measured once for both optimizers.
    const double equivalents = run["simulations"].get<double>() +
                               run["gradient_evaluations"].get<double>() * run["budget"]["gradient_cost"].get<double>();
    EXPECT_NEAR(run["simulation_equivalents"].get<double>(), equivalents, 1e-9 * equivalents);
    EXPECT_NEAR(std::stod(rows[r][column("sim.-equivalents")]), equivalents, 0.5 + 1e-9);
    // The cost column is the cost sensor's max |y| at the final design, with its unit, to the bit.
    const double cost = run["responses"]["max_abs_tip_acceleration"].get<double>();
    EXPECT_EQ(run["response_units"]["max_abs_tip_acceleration"], "m/s²");
    EXPECT_EQ(std::stod(rows[r][column("max_abs_tip_acceleration [m/s²]")]), cost);
    EXPECT_EQ(rows[r][column("reported point")], run["reported_iterate"]["point"].get<std::string>());
  }
  // The prefixed setting reached SDCC alone (SLSQP would refuse it): SDCC's first step is bounded by
  // the initial ξ = 0.05 in the W-norm (W = I), so in the max norm too (the default ξ is 0.1).
  for (const char* formulation : {"ks", "grid_max"}) {
    nlohmann::json run;
    std::ifstream(out / (std::string("sdcc-adjoint-") + formulation + ".json")) >> run;
    ASSERT_GE(run["history"].size(), 2u);
    EXPECT_GT(run["history"][1]["step"].get<double>(), 0.0);
    EXPECT_LE(run["history"][1]["step"].get<double>(), 0.05 * (1 + 1e-12));
  }
  // Two panels (cost, violation) per (formulation, gradient), in each a curve per run and its reported
  // point ringed (a block of its own, untitled): in the cost panel at the reported iteration's
  // simulation-equivalents and at the distance of the reported cost to the best feasible one, the
  // record's own figures (the data are written to 17 digits).
  const std::vector<test::PlotBlock> blocks = test::readPlotBlocks(out / "convergence.dat");
  ASSERT_EQ(blocks.size(), 2u * 4 * 2);  // per formulation: cost curves, their marks, violation curves, marks
  for (std::size_t f = 0; f < 2; ++f) {
    const std::string formulation = f == 0 ? "ks" : "grid_max";
    std::vector<nlohmann::json> runs;
    double best = INFINITY;
    for (const char* optimizer : {"sdcc", "slsqp"}) {
      runs.emplace_back();
      std::ifstream(out / (std::string(optimizer) + "-adjoint-" + formulation + ".json")) >> runs.back();
      if (runs.back()["feasible"].get<bool>()) best = std::min(best, runs.back()["cost_functional"]["final"].get<double>());
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const auto& [title, marks] = blocks[8 * f + 2 + i];
      EXPECT_EQ(title, "(marks)");
      ASSERT_EQ(marks.size(), 1u);
      const nlohmann::json& r = runs[i];
      for (const nlohmann::json& h : r["history"])
        if (h["iteration"] == r["reported_iterate"]["iteration"]) {
          EXPECT_NEAR(marks[0].first, h["simulation_equivalents"].get<double>(), 1e-12 * marks[0].first);
        }
      const double distance = std::max(std::abs(r["cost_functional"]["final"].get<double>() - best), 1e-10 * best);
      EXPECT_NEAR(marks[0].second, distance, 1e-15 * distance + 1e-15 * best) << formulation << " " << i;
    }
  }
  std::stringstream script;
  script << std::ifstream(out / "convergence.gp").rdbuf();
  EXPECT_NE(script.str().find("set logscale y"), std::string::npos);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace mbsopt
