// The scene argument of the commands: a YAML file or the name of a built-in scene, with its
// `--set name=value` overrides.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "mbsopt/problems/scene_file.hpp"

namespace mbsopt {

struct SceneArgument {
  std::string scene;              ///< a path to a .yaml file, or a built-in name
  std::vector<std::string> sets;  ///< "name=value"
};

/// Adds the positional scene argument (and `--set` when `with_overrides`) to a subcommand.
void addSceneArgument(CLI::App& command, SceneArgument& argument, bool with_overrides);

/// The file, or the built-in scene of that name; a SceneError when neither exists.
SceneSource resolveScene(const std::string& scene);

/// One override from its name and the value as typed (a number, optionally with `deg`; a word for a
/// word setting such as settings.closure).
ParameterOverride parseOverride(const SceneSource& source, const std::string& name, const std::string& text);

/// Parses "name=value" (value a number, optionally with `deg`, or a word setting's word); errors name the scene.
std::vector<ParameterOverride> parseOverrides(const SceneSource& source, const std::vector<std::string>& sets);

/// Runs a command's work on the scene: a run's failure that escapes it (a SimulationError: a loop
/// that cannot close, Newton on a step too large) becomes the scene's error at the line of the element
/// it names (failureAt), as `mbsopt simulate` reports it.
void locatingRunFailures(const SceneArgument& argument, const std::function<void()>& work);

}  // namespace mbsopt
