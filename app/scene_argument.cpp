#include "app/scene_argument.hpp"

#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {

void addSceneArgument(CLI::App& command, SceneArgument& argument, bool with_overrides) {
  command.add_option("scene", argument.scene,
                     "A scene file (YAML, see problems/scenes/README.md), a model file (MJCF .xml or URDF .urdf, "
                     "compiled by MuJoCo; docs/model-files.md) or a built-in scene: " +
                         builtinSceneList() + " (a file of that name in the working directory comes first)")
      ->required();
  if (!with_overrides) return;
  command
      .add_option("--set", argument.sets,
                  "Override one number of the scene by its dotted name, e.g. --set front_secondary.k=300e3 or "
                  "--set hinge.q0='45 deg', or the word of settings.closure (position | acceleration); repeat for several "
                  "('mbsopt parameters SCENE' lists the numbers)")
      ->allow_extra_args(false);
}

void locatingRunFailures(const SceneArgument& argument, const std::function<void()>& work) {
  try {
    work();
  } catch (const SimulationError& e) {
    const SceneSource source = resolveScene(argument.scene);
    throw failureAt(source, parseOverrides(source, argument.sets), e.element, e.what());
  }
}

}  // namespace mbsopt
