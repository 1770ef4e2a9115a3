// `mbsopt compare`: every combination of optimizers, gradient methods and formulations on one
// design problem, as a table (Markdown and CSV) and one convergence plot.
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerCompareCommand(CLI::App& app);

}  // namespace mbsopt
