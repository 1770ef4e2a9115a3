// `mbsopt simulate` with its integrators: the summary line and the JSON name the integrator
// and the estimated global error, a fixed-step run warns when its estimate is large, the output step
// sets the CSV's rows, and bad combinations are refused with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/command_directory.hpp"

namespace mbsopt {
namespace {

class SimulateCommand : public test::CommandDirectory {
 protected:
  int simulate(const std::string& arguments) const { return mbsopt("simulate " + arguments); }
};

// Every output names its units: the CSV's headers ("name [unit]", SI), the JSON's sensors and the
// summary's peaks; and the JSON's warnings are every one printed (the slider-crank with a longer rod
// starts off its closure, which loading moves and says twice).
TEST_F(SimulateCommand, OutputsNameTheirUnitsAndTheJsonEveryWarning) {
  ASSERT_EQ(simulate("slider_crank --set conrod_end.translation.x=0.45 --t-end 0.01 --out " + path("run.csv") +
                     " --json " + path("run.json")),
            0)
      << read("stderr");
  std::istringstream csv(read("run.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t [s],crank [rad],conrod [rad],slider [m],crank_angle [rad],slider_x [m],slider_v [m/s],slider_a [m/s²],"
            "rod_angle [rad]");
  const nlohmann::json run = json("run.json");
  for (const nlohmann::json& sensor : run["sensors"])
    if (sensor["name"] == "slider_a") EXPECT_EQ(sensor["unit"], "m/s²");
  EXPECT_NE(read("stdout").find("max |slider_v| = "), std::string::npos);
  EXPECT_NE(read("stdout").find(" m/s at t = "), std::string::npos) << read("stdout");
  const std::string warnings = read("stderr");
  ASSERT_EQ(run["warnings"].size(), 2u) << warnings;
  for (const nlohmann::json& warning : run["warnings"])
    EXPECT_NE(warnings.find(warning.get<std::string>()), std::string::npos) << warning;
}

TEST_F(SimulateCommand, AnAccuracyRunReportsItsEstimateInTheSummaryAndTheJson) {
  ASSERT_EQ(simulate("four_bar --accuracy 1e-6 --json " + path("run.json")), 0) << read("stderr");
  const std::string out = read("stdout");
  EXPECT_NE(out.find("to accuracy 1e-06: extrapolation of"), std::string::npos) << out;
  EXPECT_NE(out.find("estimated global error"), std::string::npos) << out;
  const nlohmann::json run = nlohmann::json::parse(read("run.json"));
  EXPECT_EQ(run["integrator"], "extrapolation");
  EXPECT_EQ(run["accuracy"]["absolute"], 1e-6);
  EXPECT_EQ(run["accuracy"]["relative"], 0.0);
  EXPECT_LE(run["estimated_global_error"]["weighted"].get<double>(), 0.5);
  // The weighted estimate is the largest |e| / 1e-6, decided before the combined q is moved back onto
  // the closure: the reported position estimate, after it, is below 0.5e-6 up to that correction.
  EXPECT_LE(run["estimated_global_error"]["position"].get<double>(), 0.55e-6);
  EXPECT_GE(run["runs"].size(), 2u);
  EXPECT_EQ(run["order"].get<int>(), static_cast<int>(run["runs"].size()));  // cut joints: orders 2, 3, 4, …
  for (const nlohmann::json& sensor : run["sensors"]) EXPECT_TRUE(sensor.contains("estimated_error"));
}

TEST_F(SimulateCommand, AFixedStepEstimatesItsErrorByDefaultAndNotWhenToldNot) {
  ASSERT_EQ(simulate("pendulum --t-end 1 --json " + path("on.json")), 0) << read("stderr");
  EXPECT_NE(read("stdout").find("of h/2 for the error estimate"), std::string::npos) << read("stdout");
  const nlohmann::json on = nlohmann::json::parse(read("on.json"));
  EXPECT_EQ(on["integrator"], "newmark");
  EXPECT_TRUE(on["accuracy"].is_null());
  EXPECT_GT(on["estimated_global_error"]["position"].get<double>(), 0.0);
  ASSERT_EQ(simulate("pendulum --t-end 1 --error-estimate off --json " + path("off.json")), 0) << read("stderr");
  EXPECT_NE(read("stdout").find("no error estimate"), std::string::npos) << read("stdout");
  const nlohmann::json off = nlohmann::json::parse(read("off.json"));
  EXPECT_TRUE(off["estimated_global_error"].is_null());
  EXPECT_EQ(off["steps"].get<long>() * 3, on["steps"].get<long>());  // the estimate's run at h/2: twice the steps
}

TEST_F(SimulateCommand, AFixedStepFarFromTheTruthWarns) {
  // Andrews' squeezer at h = 1 ms ends 1.5 rad from the published angles: the run completes (exit 0)
  // but says on stderr that its estimated error exceeds --warn-error.
  ASSERT_EQ(simulate("problems/scenes/hard/andrews_squeezer.yaml --dt 1e-3"), 0) << read("stderr");
  EXPECT_NE(read("stderr").find("warning: "), std::string::npos) << read("stderr");
  EXPECT_NE(read("stderr").find("exceeds --warn-error 0.001"), std::string::npos) << read("stderr");
  ASSERT_EQ(simulate("problems/scenes/hard/andrews_squeezer.yaml --accuracy 1e-5"), 0) << read("stderr");
  EXPECT_EQ(read("stderr").find("warning: "), std::string::npos) << read("stderr");
}

TEST_F(SimulateCommand, OutputRowsComeAtTheOutputStepWhateverTheSteps) {
  ASSERT_EQ(simulate("pendulum --t-end 2 --accuracy 1e-7 --output-step 0.25 --out " + path("run.csv")), 0)
      << read("stderr");
  std::istringstream csv(read("run.csv"));
  std::string line;
  std::getline(csv, line);
  std::vector<double> times;
  while (std::getline(csv, line)) times.push_back(std::stod(line.substr(0, line.find(','))));
  ASSERT_EQ(times.size(), 9u);
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_NEAR(times[k], 0.25 * static_cast<double>(k), 1e-12);
}

/// The "N Newton iterations" of the summary line on stdout.
long newtonIterations(const std::string& out) {
  const std::size_t at = out.find(" Newton iterations");
  const std::size_t start = out.rfind(' ', at - 1) + 1;
  return std::stol(out.substr(start, at - start));
}

// --fast-steps solves each step to a thousandth of its truncation error (tests/4-integrators/test_fast_steps.cpp
// for the accuracy): on the four-bar at 5 ms Newton stops 4-6 orders of magnitude sooner, at a
// contraction of 0.01-0.1 per iteration; it keeps the global error estimate, and extrapolation refuses it.
TEST_F(SimulateCommand, FastStepsTakeFewerNewtonIterationsAndExtrapolationRefusesThem) {
  ASSERT_EQ(simulate("four_bar --dt 5e-3"), 0) << read("stderr");
  const long exact = newtonIterations(read("stdout"));
  ASSERT_EQ(simulate("four_bar --dt 5e-3 --fast-steps"), 0) << read("stderr");
  EXPECT_LT(newtonIterations(read("stdout")), exact / 1.5) << read("stdout");
  EXPECT_NE(read("stdout").find("estimated global error"), std::string::npos) << read("stdout");
  EXPECT_EQ(simulate("four_bar --fast-steps --integrator extrapolation"), 1);
  EXPECT_NE(read("stderr").find("not --fast-steps"), std::string::npos) << read("stderr");
}

TEST_F(SimulateCommand, RefusesWhatCannotBeRun) {
  EXPECT_NE(simulate("pendulum --integrator rk4"), 0);
  EXPECT_NE(read("stderr").find("rk4"), std::string::npos) << read("stderr");
  EXPECT_NE(simulate("pendulum --accuracy 1e-3 --runs 3"), 0);
  EXPECT_NE(simulate("pendulum --relative-accuracy 1e-3"), 0);  // needs --accuracy
  EXPECT_EQ(simulate("pendulum --dt 100"), 1);  // longer than the run: it would end after its end time
  EXPECT_NE(read("stderr").find("longer than the run"), std::string::npos) << read("stderr");
  EXPECT_EQ(simulate("pendulum --fast-newton --error-estimate on"), 1);
  EXPECT_NE(read("stderr").find("not --fast-newton"), std::string::npos) << read("stderr");
  EXPECT_EQ(simulate("pendulum --integrator extrapolation --set settings.gamma=0.6"), 1);
  EXPECT_NE(read("stderr").find("trapezoidal rule"), std::string::npos) << read("stderr");
}

}  // namespace
}  // namespace mbsopt
