// An optimisation run as its documented JSON record (docs/benchmarking.md, "The records"): what a
// command writes with --json, what the benchmark sweeps collect and the Python module returns.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mbsopt/design/optimization_run.hpp"

namespace mbsopt {

/// Which point a run reports, in words (reported_iterate.rule of the JSON record, the commands' --help).
extern const char* const kReportedPointRule;

/// The run as the documented JSON record (problem, optimizer, gradient, formulation, status, …).
nlohmann::json toJson(const OptimizationRun& run, const std::string& problem);
/// What relaxing each active bound is worth, as JSON: [{name, kind (constraint, lower_bound,
/// upper_bound), parameter (the bound's dotted name for --set, in SI units), bound, unit, equality, d_cost_d_bound, relaxing_lowers_cost_by, relaxed_by,
/// cost_unit_per_unit, tolerance}].
nlohmann::json boundWorthJson(const std::vector<BoundWorth>& worth, const std::string& cost_unit);
/// The verdicts as JSON: [{name, unit, value, bound | equals, excess, tolerance, met}].
nlohmann::json verdictsJson(const std::vector<ConstraintVerdict>& verdicts);

}  // namespace mbsopt
