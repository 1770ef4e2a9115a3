// `mbsopt precision` and `mbsopt simulate --every` end to end: the JSON carries the
// documented keys, Newmark's error on the pendulum falls at second order, failed runs are reported,
// bad reference files give one clean error line, and decimated CSVs keep the first and last rows.
// The sweeps are tiny (short end times, few steps, one repeat) so that each test stays well under
// a second in Release.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "tests/command_directory.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

using PrecisionCommand = test::CommandDirectory;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST_F(PrecisionCommand, WritesTheDocumentedKeys) {
  ASSERT_EQ(mbsopt("precision pendulum --set settings.end_time=0.2 --steps 4e-3,2e-3 --variants newmark,damped "
                   "--repeat 1 --target-error 1 --out " + path("out")),
            0)
      << read("stderr");
  const nlohmann::json document = json("out/precision.json");
  for (const char* key : {"command", "scene", "study", "error_measure", "steps", "variants", "damping_alpha", "repeat",
                          "reference", "quantities", "compared_times", "target_error", "cheapest", "runs"})
    EXPECT_TRUE(document.contains(key)) << key;
  EXPECT_EQ(document["study"], "integrator");
  EXPECT_NE(document["command"].get<std::string>().find("mbsopt precision pendulum"), std::string::npos);
  EXPECT_EQ(document["reference"]["kind"], "run");
  EXPECT_DOUBLE_EQ(document["reference"]["step"].get<double>(), 2e-3 / 16);
  EXPECT_EQ(document["quantities"], nlohmann::json::array({"pivot"}));  // every coordinate of the scene
  EXPECT_EQ(document["compared_times"]["count"], 50);                   // 4 ms grid points of (0, 0.2]
  ASSERT_EQ(document["runs"].size(), 4u);  // 2 variants × 2 steps
  for (const auto& run : document["runs"]) {
    for (const char* key :
         {"variant", "step", "status", "message", "error", "errors", "wall_time_s", "steps", "newton_iterations"})
      EXPECT_TRUE(run.contains(key)) << key;
    EXPECT_EQ(run["status"], "ok");
    EXPECT_GT(run["error"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(run["errors"]["pivot"].get<double>(), run["error"].get<double>());
    EXPECT_GT(run["wall_time_s"].get<double>(), 0.0);
  }
  EXPECT_EQ(document["runs"][1]["steps"], 100);  // newmark at 2 ms over 0.2 s
  EXPECT_EQ(document["cheapest"]["status"], "ok");
  EXPECT_TRUE(std::filesystem::exists(path("out/work_precision.dat")));
  EXPECT_TRUE(std::filesystem::exists(path("out/work_precision.gp")));
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    EXPECT_TRUE(std::filesystem::exists(path("out/work_precision.png")));
  }
}

TEST_F(PrecisionCommand, NewmarkErrorFallsAtSecondOrderOnThePendulum) {
  // The trapezoidal rule (β = 1/4, γ = 1/2) against a run at h/16 of the smallest step: each halving
  // divides the error by 4 in the asymptotic range (by 4.00 at these steps).
  ASSERT_EQ(mbsopt("precision pendulum --set settings.end_time=1 --steps 4e-3,2e-3,1e-3,5e-4 --variants newmark "
                   "--repeat 1 --out " + path("out")),
            0)
      << read("stderr");
  const nlohmann::json runs = json("out/precision.json")["runs"];
  ASSERT_EQ(runs.size(), 4u);
  for (std::size_t i = 1; i < runs.size(); ++i) {
    ASSERT_EQ(runs[i]["status"], "ok");
    EXPECT_DOUBLE_EQ(runs[i]["step"].get<double>(), runs[i - 1]["step"].get<double>() / 2);
    const double ratio = runs[i - 1]["error"].get<double>() / runs[i]["error"].get<double>();
    EXPECT_GT(ratio, 3.0) << "h = " << runs[i]["step"];
    EXPECT_LT(ratio, 5.0) << "h = " << runs[i]["step"];
  }
}

TEST_F(PrecisionCommand, AFailingRunIsReportedAsFailed) {
  // Two Newton iterations per step: enough at 1 ms, not at 0.1 s on a 90° swing.
  ASSERT_EQ(mbsopt("precision pendulum --set settings.end_time=0.5 --set settings.max_newton_iterations=2 "
                   "--steps 0.1,1e-3 --variants newmark --repeat 1 --out " + path("out")),
            0)
      << read("stderr");
  const nlohmann::json runs = json("out/precision.json")["runs"];
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0]["step"], 0.1);
  EXPECT_EQ(runs[0]["status"], "failed");
  EXPECT_TRUE(runs[0]["error"].is_null());
  EXPECT_NE(runs[0]["message"].get<std::string>().find("Newton"), std::string::npos) << runs[0]["message"];
  EXPECT_EQ(runs[1]["status"], "ok");
  EXPECT_NE(read("stdout").find("failed"), std::string::npos);
}

TEST_F(PrecisionCommand, ComparesWithAReferenceFileAtItsTimes) {
  // A reference written by `simulate --every`: rows every 2 ms, on the grid of both swept steps.
  ASSERT_EQ(mbsopt("simulate pendulum --set settings.end_time=0.2 --dt 1e-4 --every 20 --out " + path("ref.csv")), 0)
      << read("stderr");
  ASSERT_EQ(mbsopt("precision pendulum --set settings.end_time=0.2 --reference " + path("ref.csv") +
                   " --steps 2e-3,1e-3 --variants newmark --repeat 1 --out " + path("out")),
            0)
      << read("stderr");
  const nlohmann::json document = json("out/precision.json");
  EXPECT_EQ(document["reference"]["kind"], "file");
  EXPECT_EQ(document["quantities"], nlohmann::json::array({"angle", "rate", "bob_x", "bob_y"}));  // its sensors
  EXPECT_EQ(document["compared_times"]["count"], 101);  // t = 0, 2 ms, ..., 0.2 s
  for (const auto& run : document["runs"]) {
    EXPECT_EQ(run["status"], "ok");
    EXPECT_LT(run["error"].get<double>(), 1e-3);
  }
}

TEST_F(PrecisionCommand, ABadReferenceFileGivesOneErrorLine) {
  const auto expectOneLine = [&](const std::string& csv, const std::string& says) {
    std::ofstream(path("bad.csv")) << csv;
    EXPECT_EQ(mbsopt("precision pendulum --reference " + path("bad.csv") + " --steps 2e-3,1e-3 --repeat 1"), 1);
    const std::vector<std::string> errors = lines(read("stderr"));
    ASSERT_EQ(errors.size(), 1u) << read("stderr");
    EXPECT_NE(errors[0].find("bad.csv"), std::string::npos) << errors[0];
    EXPECT_NE(errors[0].find(says), std::string::npos) << errors[0];
  };
  expectOneLine("t,angel\n0,1.5\n", "'angel' is neither a coordinate nor a sensor");
  expectOneLine("t,angle\n0,1.5\n0.003,1.4\n", "not on the grid of the step 0.002 s");
  expectOneLine("t,angle\n0,1.5\n0.002,x\n", "'x' is not a finite number");
  expectOneLine("t,angle\n", "no rows");
}

TEST_F(PrecisionCommand, GradientStudyOnASmallDesignProblem) {
  std::ofstream(path("chain.yaml")) << test::kOpenChainProblem;
  ASSERT_EQ(mbsopt("precision " + path("chain.yaml") + " --gradients --set settings.end_time=0.3 --steps 4e-3,2e-3 "
                   "--variants adjoint,direct --out " + path("out")),
            0)
      << read("stderr");
  const nlohmann::json document = json("out/precision.json");
  EXPECT_EQ(document["study"], "gradients");
  EXPECT_EQ(document["reference"]["variant"], "direct");
  EXPECT_DOUBLE_EQ(document["reference"]["step"].get<double>(), 2e-3 / 4);
  ASSERT_EQ(document["functionals"].size(), 5u);  // the cost and 2 × 2 constraints
  ASSERT_EQ(document["runs"].size(), 4u);
  for (const auto& run : document["runs"]) {
    EXPECT_EQ(run["status"], "ok") << run["message"];
    EXPECT_EQ(run["errors"].size(), 5u);
    EXPECT_GT(run["error"].get<double>(), 0.0);  // a discretisation error of O(h²) against h/4
    EXPECT_LT(run["error"].get<double>(), 0.5);
  }
}

TEST(SimulateEvery, WritesEveryNthTimePointAndTheLast) {
  const std::filesystem::path csv =
      std::filesystem::temp_directory_path() / ("mbsopt_every_" + std::to_string(::getpid()) + ".csv");
  // 11 equal steps of 0.0105/11 s (the fewest of at most 1 ms, ending at 0.0105 s): time points 0..11,
  // every 5th is 0, 5, 10, then the last, 11.
  const std::string command = std::string(MBSOPT_EXECUTABLE) +
                              " simulate pendulum --set settings.end_time=0.0105 --every 5 --out " + csv.string() +
                              " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(csv);
  std::vector<double> times;
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.substr(0, 6), "t [s],");
  while (std::getline(in, line)) times.push_back(std::stod(line.substr(0, line.find(','))));
  ASSERT_EQ(times.size(), 4u);
  EXPECT_DOUBLE_EQ(times[0], 0.0);
  EXPECT_DOUBLE_EQ(times[1], 5 * 0.0105 / 11);
  EXPECT_DOUBLE_EQ(times[2], 10 * 0.0105 / 11);
  EXPECT_DOUBLE_EQ(times[3], 0.0105);
  std::filesystem::remove(csv);
}

}  // namespace
}  // namespace mbsopt
