// `mbsopt precision`: work-precision studies: the integrator's error against its wall time
// over a ladder of steps and variants, or, with --gradients, that of every design-gradient method.
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerPrecisionCommand(CLI::App& app);

}  // namespace mbsopt
