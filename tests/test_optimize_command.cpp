// `mbsopt optimize` end to end on the open chain (3 design variables, an acceleration cost, KS
// constraints): the JSON carries the documented keys, the design respects the bounds, the run
// lowers the cost without violating the constraints, and the responses agree with a separate
// evaluation of the final design.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "problems/scene_file.hpp"
#include "sensitivity/design_evaluation.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

TEST(OptimizeCommand, WritesTheDocumentedKeysAndLowersTheCost) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("mbsopt_optimize_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  const std::filesystem::path scene = directory / "chain.yaml", json = directory / "chain.json";
  std::ofstream(scene) << test::kOpenChainProblem;
  const std::string command = std::string(MBSOPT_EXECUTABLE) + " optimize " + scene.string() +
                              " --optimizer slsqp --formulation ks --max-iter 15 --json " + json.string() + " > " +
                              (directory / "stdout").string();
  ASSERT_EQ(std::system(command.c_str()), 0);
  nlohmann::json r;
  std::ifstream(json) >> r;
  for (const char* key : {"problem", "optimizer", "gradient", "formulation", "status", "design", "responses", "cost",
                          "max_violation", "iterations", "simulations", "gradient_evaluations", "simulation_equivalents",
                          "wall_time_s", "history"})
    EXPECT_TRUE(r.contains(key)) << key;
  EXPECT_EQ(r["optimizer"], "slsqp");
  EXPECT_EQ(r["gradient"], "adjoint");
  const DesignProblem problem = loadDesignProblem({"chain.yaml", test::kOpenChainProblem});
  const auto design = r["design"].get<std::vector<double>>();
  ASSERT_EQ(design.size(), problem.design.variables.size());  // SI, without b_{k+1}
  for (std::size_t i = 0; i < design.size(); ++i) {
    EXPECT_GE(design[i], problem.design.variables[i].lower);
    EXPECT_LE(design[i], problem.design.variables[i].upper);
  }
  // The start (b_{k+1} = 8 m/s²) is feasible; the best feasible point can only be cheaper.
  EXPECT_LE(r["max_violation"].get<double>(), 1e-6);
  EXPECT_LT(r["cost"].get<double>(), problem.design.artificial.initial);
  const auto& history = r["history"];
  ASSERT_FALSE(history.empty());
  EXPECT_EQ(history[0]["cost"].get<double>(), problem.design.artificial.initial);
  // Each record carries its iterate in SI units: the first is the scene's own design, the last
  // accepted one lies within the bounds.
  const Eigen::VectorXd start = initialPoint(problem);
  for (std::size_t i = 0; i < design.size(); ++i)
    EXPECT_NEAR(history[0]["design"][i].get<double>(), start[static_cast<Eigen::Index>(i)] * problem.design.variables[i].scale,
                1e-12 * std::abs(problem.design.variables[i].upper));
  for (const auto& record : history) {
    ASSERT_EQ(record["design"].size(), design.size());
    for (std::size_t i = 0; i < design.size(); ++i) {
      EXPECT_GE(record["design"][i].get<double>(), problem.design.variables[i].lower);
      EXPECT_LE(record["design"][i].get<double>(), problem.design.variables[i].upper);
    }
  }
  // Every evaluation costs at least one simulation, so their time is at least that of the
  // simulations asked for (up to timing noise, a quarter).
  EXPECT_GE(r["simulation_equivalents"].get<double>(), 0.75 * r["simulations"].get<double>());
  EXPECT_LE(r["simulations"].get<long>(), 15 + 1);  // one per evaluation asked for, no point twice
  // The reported response is the grid maximum of |tip acceleration| at the final design, as a
  // simulation of that design in this process finds it (same code, same input: to round-off).
  Eigen::VectorXd x = initialPoint(problem);
  for (std::size_t i = 0; i < design.size(); ++i) x[static_cast<Eigen::Index>(i)] = design[i] / problem.design.variables[i].scale;
  const DesignResponse check = evaluateDesign(problem, transcribe(problem), x);
  const int sensor = 0;  // tip_acceleration, the cost's sensor
  const double expected = check.trajectory.sensors.col(sensor).cwiseAbs().maxCoeff();
  EXPECT_NEAR(r["responses"]["max_abs_tip_acceleration"].get<double>(), expected, 1e-9 * expected);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace mbsopt
