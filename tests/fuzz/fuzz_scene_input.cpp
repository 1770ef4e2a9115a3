// libFuzzer target over everything in mbsopt that parses user text (docs/fuzzing.md). An input is a
// scene file; its lines that start with "#!" hold command-line arguments, split at spaces, so one
// input also exercises `--set name=value` (numbers, `deg`, word settings), `--design a,b,...` and
// `--artificial x`. The shipped scenes are seeds as they are.
//
// For each input the target does what `mbsopt simulate` and `mbsopt gradcheck` do before their
// long work: parse the arguments as the commands do, parse the scene, apply the overrides, build
// the model (with its initial assembly and first evaluation), place the design point, then take up
// to three Newmark steps. An input may fail only as the program reports it: a SceneError (one line,
// naming the file), a SimulationError, or an argument error. Anything else - another exception, a
// crash, a sanitizer report, a hang (-timeout), memory beyond -rss_limit_mb, a non-finite state
// after a step that was accepted - is a finding.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "app/design_point.hpp"
#include "app/scene_argument.hpp"
#include "mbsopt/dynamics/newmark.hpp"
#include "mbsopt/problems/scene_file.hpp"
#include "tests/fuzz/input_arguments.hpp"

namespace {

constexpr const char* kPath = "fuzz.yaml";
constexpr int kSteps = 3;

/// A message the program would print: one line, naming the file.
void checkMessage(const std::string& message) {
  if (message.find('\n') != std::string::npos || !message.starts_with(kPath)) __builtin_trap();
}

void run(const std::string& text) {
  CLI::App app;
  mbsopt::SceneArgument scene;
  mbsopt::DesignPointArgument point;
  mbsopt::addSceneArgument(app, scene, true);
  mbsopt::addDesignPointOptions(app, point);
  std::vector<std::string> arguments = mbsopt::fuzz::inputArguments(text);
  arguments.emplace_back(kPath);
  std::reverse(arguments.begin(), arguments.end());  // CLI11 parses a reversed vector
  try {
    app.parse(arguments);
  } catch (const CLI::ParseError&) {
    return;  // the command line is refused before the scene is read
  }
  const mbsopt::SceneSource source{kPath, text};
  try {
    mbsopt::LoadedScene loaded = mbsopt::loadScene(source, mbsopt::parseOverrides(source, scene.sets));
    const mbsopt::Scene& s = loaded.scene;
    if (loaded.design) {
      const mbsopt::DesignProblem problem{loaded.scene, *loaded.design};
      const Eigen::VectorXd x = mbsopt::designPoint(source, problem, point);
      if (!x.allFinite()) __builtin_trap();
    }
    mbsopt::NewmarkIntegrator integrator(s.model, s.settings);
    integrator.initialize(s.q0, s.v0);
    for (int k = 0; k < kSteps && integrator.time() < s.settings.end_time; ++k) {
      integrator.step();
      if (!integrator.q().allFinite() || !integrator.v().allFinite() || !integrator.a().allFinite()) __builtin_trap();
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
