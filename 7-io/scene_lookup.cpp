#include "mbsopt/io/scene_lookup.hpp"

#include <filesystem>

#include "mbsopt/io/scene_text.hpp"

namespace mbsopt {

std::string builtinSceneList() {
  std::string names;
  for (const std::string& name : builtinSceneNames()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

SceneSource resolveScene(const std::string& scene) {
  if (scene.ends_with(".xml") || scene.ends_with(".urdf")) {  // a model file, in a scene of its own
    if (!std::filesystem::exists(scene)) throw SceneError(scene, 0, 0, "no such model file");
    std::string file;  // a YAML single-quoted scalar: ' doubled
    for (const char c : std::filesystem::path(scene).filename().string()) file += c == '\'' ? "''" : std::string(1, c);
    return {scene, "model: {file: '" + file + "'}\n"};
  }
  const bool looks_like_file = scene.ends_with(".yaml") || scene.ends_with(".yml") ||
                               scene.find('/') != std::string::npos;
  if (!looks_like_file && !std::filesystem::exists(scene)) {
    if (auto builtin = builtinScene(scene)) return *builtin;
    throw SceneError(scene, 0, 0,
                     "no such scene file, nor a built-in scene of that name (built-in: " + builtinSceneList() + ")");
  }
  return readSceneFile(scene);
}

ParameterOverride parseOverride(const SceneSource& source, const std::string& name, const std::string& text) {
  if (isWordSetting(name)) {  // the loader checks the word against the setting's choices
    if (text.empty()) throw SceneError(source.path, 0, 0, "--set " + name + "=: the value is empty");
    return ParameterOverride::ofWord(name, text);
  }
  double value = 0.0;
  std::string why;
  if (!parseNumber(text, value, why)) throw SceneError(source.path, 0, 0, name + "=" + text + ": " + why);
  return {name, value};
}

std::vector<ParameterOverride> parseOverrides(const SceneSource& source, const std::vector<std::string>& sets) {
  std::vector<ParameterOverride> overrides;
  for (const std::string& set : sets) {
    const std::size_t equals = set.find('=');
    if (equals == std::string::npos || equals == 0)
      throw SceneError(source.path, 0, 0, "--set " + quoted(set) + ": expected name=value");
    overrides.push_back(parseOverride(source, set.substr(0, equals), set.substr(equals + 1)));
  }
  return overrides;
}

}  // namespace mbsopt
