// The design problems of problems/suite/ (its README): each comes with a reference optimum that
// mbsopt did not compute, NAME.reference.json, written by the script its "command" names. Every
// problem loads; the reference was computed from the scene's own numbers; the exact gradients agree
// with each other to round-off and with central differences; and `mbsopt optimize` with each
// optimizer that reaches the optimum (kReachedBy) ends there, within what the reference says of its
// own accuracy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/gradient_checks.hpp"

namespace mbsopt {
namespace {

namespace fs = std::filesystem;

const fs::path kSuite = fs::path(MBSOPT_SOURCE_DIR) / "problems" / "suite";

/// The optimizers that reach each problem's reference from its start and say so, as the suite's
/// README reports them. The others reach it too but run to their iteration limits there, where
/// the grid maximum's peak moves between grid points (README): Ipopt on the shock isolator, CCSAQ
/// and Ipopt on the parallelogram.
const std::map<std::string, std::vector<std::string>> kReachedBy = {
    // Ipopt reaches it too but runs to its iteration limit at the grid maximum's kink (README).
    {"clothoid_transition", {"sdcc", "slsqp", "mma", "ccsaq"}},
    {"parallelogram_buffer", {"sdcc", "slsqp", "mma"}},
    // An equality, which MMA and CCSAQ cannot take; Ipopt stops by its own tolerance 1.5e-7 short
    // of the exact vertex, outside the reference's 1e-9 (README).
    {"press_slider_crank", {"sdcc", "slsqp"}},
    {"quarter_car", {"sdcc", "slsqp", "mma", "ccsaq", "ipopt"}},
    // Four equalities; SLSQP and Ipopt converge too, 1.6e-8 and 3.4e-7 above the flat minimum where
    // their tolerances on x stop them, outside the reference's 1e-9 (README).
    {"rest_to_rest", {"sdcc"}},
    {"shock_isolator", {"sdcc", "slsqp", "mma", "ccsaq"}},
    {"spring_floor", {"sdcc", "slsqp", "mma", "ipopt"}},  // CCSAQ never lowers b_{k+1} there (README)
    {"spring_preload", {"sdcc", "slsqp", "mma", "ccsaq", "ipopt"}},
    {"spring_return", {"sdcc", "slsqp", "ipopt"}},  // an equality: MMA and CCSAQ cannot take it
    {"train_couplers", {"sdcc", "slsqp", "ipopt"}},  // nineteen equalities
    // MMA runs to its evaluation limit about the optimum; CCSAQ stops on its step (xtol_rel) with c
    // 1.6e-3 above it, its cost 6e-7 above (README).
    {"tuned_mass_damper", {"sdcc", "slsqp", "ipopt"}},
    // MMA, CCSAQ and Ipopt converge too, 2.5e-8 … 1.3e-7 above the vertex (their tolerance on x
    // times the cost's slopes there), outside the reference's 1e-9 (README).
    {"wrist_pin_balance", {"sdcc", "slsqp"}},
};

std::vector<fs::path> suiteScenes() {
  std::vector<fs::path> scenes;
  for (const fs::directory_entry& entry : fs::directory_iterator(kSuite))
    if (entry.path().extension() == ".yaml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

nlohmann::json referenceOf(const fs::path& scene) {
  const fs::path path = kSuite / (scene.stem().string() + ".reference.json");
  std::ifstream in(path);
  if (!in) throw std::runtime_error("no reference " + path.string());
  nlohmann::json reference;
  in >> reference;
  return reference;
}

/// A scratch directory of this process.
fs::path scratch() {
  const fs::path directory = fs::temp_directory_path() / ("mbsopt_suite_" + std::to_string(::getpid()));
  fs::create_directories(directory);
  return directory;
}

/// Runs `mbsopt ARGUMENTS`, its standard output to `out`; the exit status.
int mbsopt(const std::string& arguments, const fs::path& out) {
  return std::system((std::string(MBSOPT_EXECUTABLE) + " " + arguments + " > " + out.string() + " 2>&1").c_str());
}

TEST(ProblemSuite, EveryProblemLoadsAndItsReferenceUsedTheScenesNumbers) {
  const std::vector<fs::path> scenes = suiteScenes();
  ASSERT_FALSE(scenes.empty());
  for (const fs::path& scene : scenes) {
    SCOPED_TRACE(scene.filename().string());
    EXPECT_NO_THROW(loadDesignProblem(readSceneFile(scene.string())));
    EXPECT_TRUE(kReachedBy.count(scene.stem().string())) << "the test lists no optimizer for it";
    const nlohmann::json reference = referenceOf(scene);
    EXPECT_EQ(reference["scene"], "problems/suite/" + scene.filename().string());
    // `mbsopt parameters` prints every number of the scene by its dotted name: the reference's data
    // are its inputs, so they must be the scene's numbers exactly.
    const fs::path listing = scratch() / "parameters.txt";
    ASSERT_EQ(mbsopt("parameters " + scene.string(), listing), 0);
    std::map<std::string, double> parameters;
    std::ifstream in(listing);
    std::string name;
    double value = 0.0;
    while (in >> name >> value) parameters[name] = value;
    ASSERT_FALSE(reference["data"].empty());
    for (const auto& [key, number] : reference["data"].items()) {
      ASSERT_TRUE(parameters.count(key)) << key << " is not a number of the scene";
      EXPECT_EQ(parameters[key], number.get<double>()) << key;
    }
  }
}

/// Every number of `a` and `b`, two JSON documents of the same shape, equal to 1e-12 relative (the
/// scripts' arithmetic is the same; another libm may round a last bit differently).
void expectSameNumbers(const nlohmann::json& a, const nlohmann::json& b, const std::string& where) {
  ASSERT_EQ(a.type(), b.type()) << where;
  if (a.is_object() || a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j) {
      if (a.is_object()) {
        ASSERT_EQ(i.key(), j.key()) << where;
      }
      expectSameNumbers(*i, *j, where + "/" + (a.is_object() ? i.key() : "[]"));
    }
  } else if (a.is_number()) {
    EXPECT_NEAR(a.get<double>(), b.get<double>(), 1e-12 * std::abs(b.get<double>())) << where;
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

// A reference is what its script prints: the scripts that take a few seconds are run again (-B: no
// bytecode left in the source tree) and their output compared with the file (the isolator's takes
// 20 s and the four-bar's 4 min: run by hand, `"command"` in each file).
TEST(ProblemSuite, TheQuickReferencesAreWhatTheirScriptsPrint) {
  const fs::path directory = scratch();
  for (const std::string name :
       {"clothoid_transition", "press_slider_crank", "rest_to_rest", "spring_floor", "spring_preload", "spring_return", "train_couplers",
        "tuned_mass_damper", "wrist_pin_balance"}) {
    const nlohmann::json reference = referenceOf(kSuite / (name + ".yaml"));
    const fs::path printed = directory / (name + ".json");
    const std::string command = "python3 -B " + (fs::path(MBSOPT_SOURCE_DIR) / "scripts" / "reference" / (name + ".py")).string() +
                                " > " + printed.string();
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    nlohmann::json again;
    std::ifstream(printed) >> again;
    expectSameNumbers(again, reference, name);
  }
}

// Both exact methods differentiate the same discrete map: equal to round-off (1e-12 of the largest
// entry; they take the same solves in another order). Central differences of the simulation agree
// with them at their best step to 1e-6: O(δ²) truncation, and the Newton tolerance (1e-10
// relative) over δ, meet near δ = 1e-4 at about 1e-8 to 1e-7 relative (test_exact_gradients.cpp).
/// Each suite problem on its own, so that ctest spreads the long ones over the cores.
class SuiteProblem : public testing::TestWithParam<std::string> {
 protected:
  fs::path scene() const { return kSuite / (GetParam() + ".yaml"); }
};

TEST_P(SuiteProblem, ExactGradientsAgreeWithEachOtherAndWithCentralDifferences) {
  const fs::path scene = this->scene();
  const DesignProblem problem = loadDesignProblem(readSceneFile(scene.string()));
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient direct = directGradient(problem, functionals, x);
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  const auto variables = static_cast<Eigen::Index>(problem.design.variables.size());
  EXPECT_GT(direct.constraints.leftCols(variables).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE(test::relativeGap(adjoint.constraints, direct.constraints), 1e-12);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

// The reference is the continuous-time optimum, or that of the problem on mbsopt's grid; mbsopt's is
// the latter, which differs by the reference's own estimate ("accuracy": "cost_relative", the Newmark
// step's period error and the grid's sampling of a peak). The optimizers stop within 1e-6 (relative,
// on x) of their optimum, and may exceed an active bound by their feasibility tolerance (1e-6 in its
// units), which moves the responses by the reference's "feasibility_allowance" where it gives one (the
// bound's multiplier times 1e-6). So every response agrees to 10 × that estimate plus that allowance,
// and the design lies (to 1e-6) in the reference's "design_range", which each reference derives from
// its own problem: the designs whose cost is within "design_cost_band" of the optimum (wider than the
// estimate where the cost is flat near its minimum), or the grid's shift of an equality's solution.
TEST_P(SuiteProblem, TheOptimizersReachTheReferenceOptimum) {
  const fs::path directory = scratch();
  const fs::path scene = this->scene();
  const std::string name = GetParam();
  const DesignProblem problem = loadDesignProblem(readSceneFile(scene.string()));
  const nlohmann::json reference = referenceOf(scene);
  const nlohmann::json& optimum = reference["optimum"];
  const double tolerance = 10.0 * reference["accuracy"]["cost_relative"].get<double>();
  ASSERT_GT(tolerance, 0.0);
  for (const std::string& optimizer : kReachedBy.at(name)) {
    SCOPED_TRACE(name + " with " + optimizer);
    const fs::path json = directory / (name + "-" + optimizer + ".json");
    ASSERT_EQ(mbsopt("optimize " + scene.string() + " --optimizer " + optimizer + " --json " + json.string(),
                     directory / "stdout"),
              0);
    nlohmann::json result;
    std::ifstream(json) >> result;
    EXPECT_EQ(result["status"], "converged") << result["message"];
    EXPECT_EQ(result["reported_iterate"]["point"], "final");  // where it converged, not an earlier point
    const nlohmann::json& allowance = reference["accuracy"].value("feasibility_allowance", nlohmann::json::object());
    for (const auto& [response, value] : optimum["responses"].items()) {
      const double expected = value.get<double>();
      EXPECT_NEAR(result["responses"][response].get<double>(), expected,
                  tolerance * std::abs(expected) + allowance.value(response, 0.0))
          << response;
    }
    const auto design = result["design"].get<std::vector<double>>();
    ASSERT_EQ(design.size(), problem.design.variables.size());
    for (std::size_t i = 0; i < design.size(); ++i) {
      const std::string& parameter = problem.design.variables[i].parameter;
      const nlohmann::json& range = reference["accuracy"]["design_range"][parameter];
      const double slack = 1e-6 * std::abs(design[i]);  // the optimizers' relative tolerance on x
      EXPECT_GE(design[i], range[0].get<double>() - slack) << parameter;
      EXPECT_LE(design[i], range[1].get<double>() + slack) << parameter;
    }
  }
}

std::vector<std::string> suiteNames() {
  std::vector<std::string> names;
  for (const fs::path& scene : suiteScenes()) names.push_back(scene.stem().string());
  return names;
}

INSTANTIATE_TEST_SUITE_P(ProblemSuite, SuiteProblem, testing::ValuesIn(suiteNames()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace mbsopt
