#include "app/parameters_command.hpp"

#include <cstdio>
#include <memory>

#include "app/scene_argument.hpp"

namespace mbsopt {

void registerParametersCommand(CLI::App& app) {
  auto argument = std::make_shared<SceneArgument>();
  CLI::App* command = app.add_subcommand(
      "parameters", "List every number of a scene by its dotted name (what --set and design problems address), "
                    "one 'name value' per line, in file order");
  addSceneArgument(*command, *argument, false);
  command->callback([argument] {
    const SceneSource source = resolveScene(argument->scene);
    loadScene(source);  // the list is only worth having for a scene that loads
    for (const auto& [name, value] : sceneParameters(source)) std::printf("%s %.17g\n", name.c_str(), value);
  });
}

}  // namespace mbsopt
