// What `mbsopt simulate` reports of a run: the peak of every sensor, the summary line, warnings
// (an estimated global error above --warn-error) and the same as JSON (--json).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mbsopt/integrators/integration.hpp"

namespace mbsopt {

struct SimulationSummary {
  std::vector<std::string> sensor_lines;  ///< "  max |NAME| = V at t = T s[ (estimated error E)]"
  std::string line;                       ///< "simulated PATH: ..."
  std::vector<std::string> warnings;
  nlohmann::json json;
};

/// The report of `integration`, a run of `settings` as `request` asked, that took `wall` seconds.
/// `warn_error`: the weighted tolerance (absolute and relative) above which an estimate is a warning.
SimulationSummary summarize(const Model& model, const std::string& path, const Integration& integration,
                            const IntegrationRequest& request, const NewmarkSettings& settings, double wall,
                            double warn_error);

}  // namespace mbsopt
