// The design point a command works at, as the command line gives it: `--design` (SI units),
// `--artificial` (b_{k+1}) and `--outside-bounds`, checked by checkedDesignPoint.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "mbsopt/io/design_point.hpp"

namespace mbsopt {

/// Adds `--design`, `--artificial` and `--outside-bounds` to `command`; `condition` ("With --gradients: ",
/// or empty) starts their help. Returns the three options.
std::vector<CLI::Option*> addDesignPointOptions(CLI::App& command, DesignPointRequest& request,
                                                const std::string& condition = "");

}  // namespace mbsopt
