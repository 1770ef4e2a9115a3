// The scene argument of the commands: a YAML file or the name of a built-in scene, with its
// `--set name=value` overrides.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "mbsopt/io/scene_lookup.hpp"

namespace mbsopt {

struct SceneArgument {
  std::string scene;              ///< a path to a .yaml file, or a built-in name
  std::vector<std::string> sets;  ///< "name=value"
};

/// Adds the positional scene argument (and `--set` when `with_overrides`) to a subcommand.
void addSceneArgument(CLI::App& command, SceneArgument& argument, bool with_overrides);

/// Runs a command's work on the scene: a run's failure that escapes it (a SimulationError: a loop
/// that cannot close, Newton on a step too large) becomes the scene's error at the line of the element
/// it names (failureAt), as `mbsopt simulate` reports it.
void locatingRunFailures(const SceneArgument& argument, const std::function<void()>& work);

}  // namespace mbsopt
