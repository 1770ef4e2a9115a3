// What a work-precision study reports (`mbsopt precision`): the table on stdout, each run as JSON,
// the log-log plot of error against time, and the cheapest run that reaches a target error.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mbsopt/design/precision_run.hpp"

namespace mbsopt {

/// One line per run: variant, h, error, time, steps and Newton iterations (when known), or why it failed.
void printPrecisionTable(const std::vector<PrecisionRun>& runs, const std::string& error_heading);

/// {variant, step, status ("ok" | "failed"), message, error, errors{name: value}, wall_time_s,
/// steps, newton_iterations}; error null when failed, the last two only for integrator runs.
nlohmann::json precisionRunJson(const PrecisionRun& run);

/// The run that reaches `target` (error ≤ target) in the least time; nullptr when none does.
const PrecisionRun* cheapestReaching(const std::vector<PrecisionRun>& runs, double target);

/// Prints which variant and step reach `target` in the least time, or that none does.
void printTarget(const std::vector<PrecisionRun>& runs, double target);

/// STEM.png (with STEM.dat, STEM.gp): error against wall time, log-log, one curve per variant, in
/// the order of the runs. Runs that failed or have a zero error are left out of the plot.
void plotWorkPrecision(const std::string& stem, const std::string& title, const std::vector<PrecisionRun>& runs,
                       const std::string& error_label);

}  // namespace mbsopt
