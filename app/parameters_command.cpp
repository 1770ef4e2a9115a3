#include "app/parameters_command.hpp"

#include <cstdio>
#include <memory>

#include "mbsopt/io/scene_text.hpp"
#include "app/scene_argument.hpp"

namespace mbsopt {

void registerParametersCommand(CLI::App& app) {
  auto argument = std::make_shared<SceneArgument>();
  CLI::App* command = app.add_subcommand(
      "parameters", "List every number of a scene by its dotted name (what --set and design problems address), "
                    "one 'name value' per line: the file's numbers in file order, then the defaults it leaves out");
  addSceneArgument(*command, *argument, false);
  command->callback([argument] {
    const SceneSource source = resolveScene(argument->scene);
    for (const auto& [name, value] : sceneParameters(source)) std::printf("%s %s\n", name.c_str(), formatNumber(value).c_str());
  });
}

}  // namespace mbsopt
