// `mbsopt benchmark`: the sweep of benchmark_plan.hpp run on this machine's threads or over the
// ranks of an MPI job, then its report (benchmark_report.hpp).
#pragma once

#include <CLI/CLI.hpp>

namespace mbsopt {

void registerBenchmarkCommand(CLI::App& app);

}  // namespace mbsopt
