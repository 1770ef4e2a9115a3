// A scene by what a user types: a YAML file's path or the name of a built-in scene, and its
// overrides as "name=value" text (the command line's --set, the Python module's set=).
#pragma once

#include <string>
#include <vector>

#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {

/// The file, or the built-in scene of that name (a name that ends in .yaml/.yml or holds a '/' is a
/// path; a file of that name in the working directory comes first); a SceneError when neither exists.
/// An MJCF (.xml) or URDF (.urdf) file is the scene `model: {file: …}` with the default settings.
SceneSource resolveScene(const std::string& scene);

/// The built-in scenes' names, comma-separated (for messages and --help).
std::string builtinSceneList();

/// One override from its name and the value as typed (a number, optionally with `deg`; a word for a
/// word setting such as settings.closure).
ParameterOverride parseOverride(const SceneSource& source, const std::string& name, const std::string& text);

/// Parses "name=value" (value a number, optionally with `deg`, or a word setting's word); errors name the scene.
std::vector<ParameterOverride> parseOverrides(const SceneSource& source, const std::vector<std::string>& sets);

}  // namespace mbsopt
