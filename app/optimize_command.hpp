// `mbsopt optimize`: one optimizer on one design problem, with the gradients of one method.
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerOptimizeCommand(CLI::App& app);

}  // namespace mbsopt
