// Scene files (problems/scenes/README.md): a YAML description of a mechanism, its initial state and
// its integration settings, built into a Scene. Every error names the file, line and column.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"

namespace mbsopt {

/// The size of a model a scene file may describe (problems/scenes/README.md, "Limits"): the
/// integrator's matrices are dense, n × n in the coordinates and m × n in the closure equations.
struct SceneLimits {
  std::size_t entries_per_section = 10000;  ///< tracks, elements, bodies, forces, cuts, sensors
  int coordinates = 2000;                   ///< joint coordinates n
  int closure_equations = 2000;             ///< loop-closure equations m
};
inline constexpr SceneLimits kSceneLimits{};

/// A scene file's text and the path under which errors name it.
struct SceneSource {
  std::string path;
  std::string text;
};

/// A bad scene: "path:line:column: what" (line and column 1-based; 0 when unknown).
class SceneError : public std::runtime_error {
 public:
  SceneError(const std::string& path, int line, int column, const std::string& what);
  const std::string& path() const { return path_; }
  int line() const { return line_; }
  int column() const { return column_; }
  /// What is wrong, without the location.
  const std::string& reason() const { return reason_; }

 private:
  std::string path_, reason_;
  int line_, column_;
};

/// A `--set name=value` override of one parameter of the file: a number, or the word of a setting
/// whose value is a word (isWordSetting: `settings.closure=acceleration`).
struct ParameterOverride {
  ParameterOverride(std::string name_, double value_) : name(std::move(name_)), value(value_) {}
  static ParameterOverride ofWord(std::string name_, std::string word_) {
    ParameterOverride o(std::move(name_), 0.0);
    o.word = std::move(word_);
    return o;
  }
  std::string name;
  double value = 0.0;
  std::string word;  ///< the value of a word setting, as typed; empty for a number
  /// Where the value comes from, as the messages name it ("--set", "the design point", a bound's name).
  std::string origin = "--set";
};

/// Whether `dotted_name` is a setting whose value is a word, not a number: `settings.closure`.
bool isWordSetting(const std::string& dotted_name);

struct SceneLocation {
  int line = 0, column = 0;  ///< 1-based
};

struct LoadedScene {
  Scene scene;
  std::vector<std::string> warnings;  ///< e.g. how far the initial state was moved to close the loops
  std::map<std::string, SceneLocation> locations;  ///< where each named entry is declared
  std::optional<DesignDescription> design;         ///< the `design:` section, when the file has one
  /// What `model: {ignore: …}` left out of a model file, a line per feature (empty without one).
  std::vector<std::string> left_out;
};

/// A failure of a run of the scene (a SimulationError's message and the element it names) as the
/// scene's error, at the line where the element is declared (at the file when it names none, or
/// the scene does not load with these overrides).
SceneError failureAt(const SceneSource& source, const std::vector<ParameterOverride>& overrides,
                     const std::string& element, const std::string& what);

/// The scene and its `design:` section as a design problem; a SceneError when it has none.
DesignProblem loadDesignProblem(const SceneSource& source, const std::vector<ParameterOverride>& overrides = {});

/// Reads a file; throws SceneError when it cannot be read.
SceneSource readSceneFile(const std::string& path);
/// The scenes of problems/scenes/, compiled into the library, by base name ("pendulum").
std::optional<SceneSource> builtinScene(const std::string& name);
std::vector<std::string> builtinSceneNames();

/// Parses, applies the overrides, builds and assembles the initial state onto the loop closure.
/// Throws SceneError for anything wrong with the file or the overrides.
LoadedScene loadScene(const SceneSource& source, const std::vector<ParameterOverride>& overrides = {});

/// Every number of the file by its dotted name, with its value, in file order; then the numbers it
/// leaves at their defaults (settings, model parameters, initial coordinates and rates), which
/// `--set` can address too. Builds the scene.
std::vector<std::pair<std::string, double>> sceneParameters(const SceneSource& source);

}  // namespace mbsopt
