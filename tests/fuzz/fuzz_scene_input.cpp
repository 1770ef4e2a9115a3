// libFuzzer target over everything in mbsopt that parses user text (docs/fuzzing.md). An input is a
// scene file; its lines that start with "#!" hold command-line arguments, split at spaces, so one
// input also exercises `--set name=value` (numbers, `deg`, word settings), `--design a,b,...`,
// `--artificial x`, `--outside-bounds`, `--optimizer`, `--gradient` and `--formulation`. The shipped
// scenes are seeds as they are.
//
// For each input the target does what the commands do: parse the arguments as they do, parse the
// scene, apply the overrides, build the model (with its initial assembly and first evaluation), take
// up to three Newmark steps (`simulate`); with a design section, load it as a design problem over
// those few steps, evaluate it with gradients at the checked design point (`gradcheck`,
// Problem.evaluate) and run the optimizer for a few iterations (`optimize`, Problem.optimize). An
// input may fail only as the program reports it: a SceneError (one line, naming the file), a
// SimulationError, an std::invalid_argument or std::length_error (a value or a size refused), or an
// argument error. Anything else - another exception, a crash, a sanitizer report, a hang (-timeout),
// memory beyond -rss_limit_mb, a non-finite state after a step that was accepted, a non-finite value
// or gradient that was not refused, a converged run with a non-finite answer - is a finding.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/design_nlp.hpp"
#include "mbsopt/design/optimization_run.hpp"
#include "app/design_point.hpp"
#include "app/scene_argument.hpp"
#include "tests/fuzz/input_arguments.hpp"

namespace {

constexpr const char* kPath = "fuzz.yaml";
constexpr int kSteps = 3;
constexpr int kOptimizerIterations = 3;

/// A message the program would print: one line, naming the file.
void checkMessage(const std::string& message) {
  if (message.find('\n') != std::string::npos || !message.starts_with(kPath)) __builtin_trap();
}

bool finite(const nlohmann::json& values) {
  for (const auto& [key, value] : values.items())
    if (!value.is_number() || !std::isfinite(value.get<double>())) return false;
  return true;
}

struct Arguments {
  mbsopt::SceneArgument scene;
  mbsopt::DesignPointRequest point;
  mbsopt::RunChoice choice;
};

/// The design commands on the scene's first few steps: the checked point evaluated with gradients,
/// then a short optimisation from the start.
void runDesign(const mbsopt::SceneSource& source, std::vector<mbsopt::ParameterOverride> overrides,
               const mbsopt::Scene& scene, const Arguments& arguments) {
  overrides.emplace_back("settings.end_time", std::min(scene.settings.end_time, kSteps * scene.settings.step));
  const mbsopt::DesignProblem problem = mbsopt::loadDesignProblem(source, overrides);
  const Eigen::VectorXd x = mbsopt::checkedDesignPoint(source, overrides, problem, arguments.point);
  if (!x.allFinite()) __builtin_trap();
  const mbsopt::RunChoice choice = mbsopt::resolvedChoice(problem, arguments.choice);
  mbsopt::DesignNlp nlp(mbsopt::formulatedProblem(problem, choice), choice.gradient);
  mbsopt::NlpEvaluation at;
  nlp.evaluate(x, true, at);
  if (!std::isfinite(at.cost) || !at.constraints.allFinite() || !at.cost_gradient.allFinite() ||
      !at.constraint_jacobian.allFinite())
    __builtin_trap();
  mbsopt::RunChoice run = arguments.choice;
  run.max_iterations = kOptimizerIterations;
  run.budget.simulation_equivalents = 30;
  const mbsopt::OptimizationRun result = mbsopt::runOptimization(problem, run, {});
  if (!result.result.x.allFinite() || !finite(result.responses)) __builtin_trap();
  if (result.result.status == mbsopt::OptimizerStatus::Converged && !std::isfinite(result.result.reported_cost))
    __builtin_trap();
}

void run(const std::string& text) {
  CLI::App app;
  Arguments arguments;
  mbsopt::addSceneArgument(app, arguments.scene, true);
  mbsopt::addDesignPointOptions(app, arguments.point);
  app.add_option("--optimizer", arguments.choice.optimizer)->check(CLI::IsMember(mbsopt::optimizerNames()));
  app.add_option("--gradient", arguments.choice.gradient)->check(CLI::IsMember(mbsopt::gradientMethodChoices()));
  app.add_option("--formulation", arguments.choice.formulation)->check(CLI::IsMember(mbsopt::formulationNames()));
  std::vector<std::string> words = mbsopt::fuzz::inputArguments(text);
  words.emplace_back(kPath);
  std::reverse(words.begin(), words.end());  // CLI11 parses a reversed vector
  try {
    app.parse(words);
  } catch (const CLI::ParseError&) {
    return;  // the command line is refused before the scene is read
  }
  const mbsopt::SceneSource source{kPath, text};
  try {
    const std::vector<mbsopt::ParameterOverride> overrides = mbsopt::parseOverrides(source, arguments.scene.sets);
    mbsopt::LoadedScene loaded = mbsopt::loadScene(source, overrides);
    const mbsopt::Scene& s = loaded.scene;
    mbsopt::NewmarkIntegrator integrator(s.model, s.settings);
    integrator.initialize(s.q0, s.v0);
    for (int k = 0; k < kSteps && integrator.time() < s.settings.end_time; ++k) {
      integrator.step();
      if (!integrator.q().allFinite() || !integrator.v().allFinite() || !integrator.a().allFinite()) __builtin_trap();
    }
    if (!loaded.design) return;
    try {
      runDesign(source, overrides, s, arguments);
    } catch (const std::invalid_argument&) {  // a design point or a choice refused, a response not finite
    } catch (const std::length_error&) {      // beyond a documented limit
    }
  } catch (const mbsopt::SceneError& e) {
    checkMessage(e.what());
  } catch (const mbsopt::SimulationError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  run(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
