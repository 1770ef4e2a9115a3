// `mbsopt parameters`: the dotted names and values of every number of a scene.
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerParametersCommand(CLI::App& app);

}  // namespace mbsopt
