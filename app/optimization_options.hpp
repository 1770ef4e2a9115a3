// The command-line flags of an optimisation run and of a sweep of runs (`mbsopt optimize`,
// `compare`, `benchmark`), into the library's RunChoice and SweepAxes.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "mbsopt/design/optimization_run.hpp"

namespace mbsopt {

/// Adds the limits of a run to a command: --budget (simulation-equivalents), --wall-time, --gradient-cost
/// (alike for every optimizer) and --max-iter (each optimizer's own count).
void addBudgetOptions(CLI::App& command, RunChoice& choice);

/// Adds --setting (repeatable NAME=VALUE, the optimizer's own settings) to a command.
void addSettingOption(CLI::App& command, std::vector<std::string>& settings);

/// Adds --optimizers, --gradients, --formulations and --epsilon (into `shared`) to a command.
void addSweepOptions(CLI::App& command, SweepAxes& axes, RunChoice& shared);

}  // namespace mbsopt
