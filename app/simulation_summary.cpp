#include "app/simulation_summary.hpp"

#include <cstdio>
#include <sstream>

#include "mbsopt/model/units.hpp"

namespace mbsopt {

namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

/// "12000 steps of 0.001 s" or "4 runs at 0.004 s / 1 ... 4 (order 4)".
std::string stepsText(const Integration& integration, const IntegrationRequest& request) {
  const EstimatedRun& run = integration.run;
  const long steps = run.trajectory.statistics.steps;
  const IntegratorInfo& integrator = integratorInfo(request.integrator.name);
  const bool newmark = !integrator.extrapolated && !integrator.variable_steps;
  if (newmark && !request.accuracy) {
    // With the estimate, a run at h and one at h/2 (twice as many steps).
    const long own = integration.estimated ? steps / 3 : steps;
    std::string text = std::to_string(own) + " steps of " + format("%.6g", run.steps.front()) + " s";
    if (integration.estimated) text += " (and " + std::to_string(steps - own) + " of h/2 for the error estimate)";
    return text;
  }
  if (integrator.variable_steps) {
    std::string text = "adaptive Newmark (order 2, local error control), steps up to " + format("%g", run.steps.front()) +
                       " s, " + std::to_string(steps) + " steps in all";
    if (integration.estimated && !request.accuracy) text += " (a third of them the run's, the rest its halved steps' for the error estimate)";
    return text + ", " + std::to_string(run.trajectory.statistics.rejected_steps) + " rejected by the local error or Newton";
  }
  const std::string runs = std::to_string(run.steps.size()) + " runs at H/1 ... H/" + std::to_string(run.steps.size()) +
                           ", H = " + format("%g", run.steps.front()) + " s";
  if (newmark)  // driven by accuracy: the result is the run at H/2
    return "Newmark at h = " + format("%g", run.steps.back()) + " s (order 2, its error estimated from the run at " +
           format("%g", run.steps.front()) + " s), " + std::to_string(steps) + " steps in all";
  return "extrapolation of " + runs + " (order " + std::to_string(run.order) + "), " + std::to_string(steps) +
         " steps in all";
}

}  // namespace

SimulationSummary summarize(const Model& model, const std::string& path, const Integration& integration,
                            const IntegrationRequest& request, const NewmarkSettings& settings, double wall,
                            double warn_error) {
  SimulationSummary out;
  const EstimatedRun& run = integration.run;
  const Trajectory& trajectory = run.trajectory;
  const IntegratorStatistics& stats = trajectory.statistics;
  nlohmann::json sensors = nlohmann::json::array();
  for (std::size_t s = 0; s < model.sensors().size(); ++s) {
    const Eigen::Index column = static_cast<Eigen::Index>(s);
    Eigen::Index at = 0;
    const double peak = trajectory.sensors.col(column).cwiseAbs().maxCoeff(&at);
    const std::string unit = sensorSiUnit(model, model.sensors()[s]);
    std::string line = "  max |" + model.sensors()[s].name + "| = " + format("%.6g", peak) + " " + unit + " at t = " +
                       format("%.4g", trajectory.time[at]) + " s";
    nlohmann::json record = {{"name", model.sensors()[s].name}, {"unit", unit}, {"max_abs", peak}, {"at_time", trajectory.time[at]}};
    if (integration.estimated) {
      const double error = run.sensor_error.col(column).cwiseAbs().maxCoeff();
      line += " (estimated error " + format("%.2g", error) + ")";
      record["estimated_error"] = error;
    }
    out.sensor_lines.push_back(line);
    sensors.push_back(record);
  }

  out.json = {{"scene", path},
              {"integrator", request.integrator.name},
              {"end_time", settings.end_time},
              {"output_points", trajectory.time.size()},
              {"runs", run.steps},
              {"order", run.order},
              {"steps", stats.steps},
              {"rejected_steps", stats.rejected_steps},
              {"newton_iterations", stats.newton_iterations},
              {"max_closure_error", stats.max_closure_error},
              {"max_relative_newton_residual", stats.max_relative_residual},
              {"wall_time_s", wall},
              {"sensors", sensors}};
  out.json["runs_unit"] =
      "s (the step of every Newmark run of the result, in order; for adaptive, its largest step and that halved; steps "
      "counts the rejected attempts' too, except the steps of a run that failed)";
  std::string line = "simulated " + path;
  if (request.accuracy) {
    line += " to accuracy " + format("%g", request.accuracy->absolute);
    if (request.accuracy->relative > 0.0) line += " (relative " + format("%g", request.accuracy->relative) + ")";
    out.json["accuracy"] = {{"absolute", request.accuracy->absolute}, {"relative", request.accuracy->relative}};
  } else {
    out.json["accuracy"] = nullptr;
  }
  line += ": " + stepsText(integration, request) + ", " + std::to_string(stats.newton_iterations) +
          " Newton iterations, max closure error " + format("%.3g", stats.max_closure_error) +
          ", max relative Newton residual " + format("%.3g", stats.max_relative_residual);
  if (integration.control) {
    const AccurateRun& control = *integration.control;
    line += ", " + std::to_string(control.rejected.size()) + " attempt" + (control.rejected.size() == 1 ? "" : "s") +
            " rejected";
    nlohmann::json rejected = nlohmann::json::array();
    for (const AccuracyAttempt& a : control.rejected)
      rejected.push_back({{"macro_step", a.macro_step},
                          {"runs", a.runs},
                          {"weighted_error", std::isfinite(a.weighted_error) ? nlohmann::json(a.weighted_error) : nullptr},
                          {"failure", a.failure}});
    out.json["macro_step"] = control.macro_step;
    out.json["rejected_attempts"] = rejected;
  }
  if (integration.estimated) {
    Eigen::Index coordinate = 0, point = 0;
    const double position = run.q_error.cwiseAbs().maxCoeff(&coordinate, &point);
    const std::string name = model.coordinates()[static_cast<std::size_t>(coordinate)].name;
    const ErrorTolerance warn{warn_error, warn_error};
    const double weighted = weightedErrorNorm(run.q_error, trajectory.q, warn);
    line += ", estimated global error " + format("%.2g", position) + " (" + name + " at t = " +
            format("%.4g", trajectory.time[point]) + " s" +
            (run.round_off_floor ? "; round-off floor " + format("%.2g", *run.round_off_floor) + " included" : "") + ")";
    nlohmann::json estimate = {{"position", position},
                               {"position_unit", "m or rad, the coordinate's own"},
                               {"largest_at", {{"coordinate", name}, {"time", trajectory.time[point]}}},
                               {"velocity", run.velocityError()},
                               {"round_off_floor", run.round_off_floor ? nlohmann::json(*run.round_off_floor) : nullptr}};
    if (request.accuracy) {
      const double relative = integration.control->weighted_error;
      line += ", " + format("%.2g", relative) + " of the tolerance";
      estimate["weighted"] = relative;
    }
    out.json["estimated_global_error"] = estimate;
    if (weighted > 1.0)
      out.warnings.push_back(path + ": the estimated global error of '" + name + "', " + format("%.2g", position) +
                             " at t = " + format("%.4g", trajectory.time[point]) + " s, exceeds --warn-error " +
                             format("%g", warn_error) + " (absolute and relative): take a smaller step or --accuracy");
  } else {
    line += ", no error estimate";
    out.json["estimated_global_error"] = nullptr;
  }
  const IntegratorInfo& integrator = integratorInfo(request.integrator.name);
  if (request.accuracy || integrator.extrapolated || integrator.variable_steps || request.output_step > 0.0)  // the peaks' points
    line += ", " + std::to_string(trajectory.time.size()) + " output times";
  line += ", wall time " + format("%.3g", wall) + " s";
  out.json["warnings"] = out.warnings;
  out.line = line;
  return out;
}

}  // namespace mbsopt
