// `mbsopt simulate`: runs a scene and writes its trajectory.
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerSimulateCommand(CLI::App& app);

}  // namespace mbsopt
