#include "mbsopt/design/precision_report.hpp"

#include <algorithm>
#include <cstdio>

#include "mbsopt/io/gnuplot.hpp"

namespace mbsopt {

namespace {

std::string countText(const std::optional<long>& count) { return count ? std::to_string(*count) : "-"; }

}  // namespace

void printPrecisionTable(const std::vector<PrecisionRun>& runs, const std::string& error_heading) {
  std::printf("%-21s %10s %14s %11s %9s %9s\n", "variant", "h [s]", error_heading.c_str(), "time [s]", "steps",
              "Newton");
  for (const PrecisionRun& run : runs) {
    if (run.failed) {
      std::printf("%-21s %10.4g %14s %11.4g  %s\n", run.variant.c_str(), run.step, "failed", run.seconds,
                  run.message.c_str());
      continue;
    }
    std::printf("%-21s %10.4g %14.4e %11.4g %9s %9s\n", run.variant.c_str(), run.step, run.error, run.seconds,
                countText(run.steps).c_str(), countText(run.newton_iterations).c_str());
  }
}

nlohmann::json precisionRunJson(const PrecisionRun& run) {
  nlohmann::json errors = nlohmann::json::object();
  for (const auto& [name, error] : run.errors) errors[name] = error;
  nlohmann::json json = {{"variant", run.variant},
                         {"step", run.step},
                         {"status", run.failed ? "failed" : "ok"},
                         {"message", run.message},
                         {"error", run.failed ? nlohmann::json(nullptr) : nlohmann::json(run.error)},
                         {"errors", errors},
                         {"wall_time_s", run.seconds}};
  if (run.steps) json["steps"] = *run.steps;
  if (run.newton_iterations) json["newton_iterations"] = *run.newton_iterations;
  if (run.estimated_error) json["estimated_error"] = *run.estimated_error;
  return json;
}

const PrecisionRun* cheapestReaching(const std::vector<PrecisionRun>& runs, double target) {
  const PrecisionRun* best = nullptr;
  for (const PrecisionRun& run : runs)
    if (!run.failed && run.error <= target && (!best || run.seconds < best->seconds)) best = &run;
  return best;
}

void printTarget(const std::vector<PrecisionRun>& runs, double target) {
  if (const PrecisionRun* best = cheapestReaching(runs, target)) {
    std::printf("target error %.3g: reached in the least time by %s at h = %.4g s (error %.3g, %.4g s)\n", target,
                best->variant.c_str(), best->step, best->error, best->seconds);
    return;
  }
  const PrecisionRun* closest = nullptr;
  for (const PrecisionRun& run : runs)
    if (!run.failed && (!closest || run.error < closest->error)) closest = &run;
  if (closest)
    std::printf("target error %.3g: no run reaches it (the smallest error, %.3g, is %s's at h = %.4g s)\n", target,
                closest->error, closest->variant.c_str(), closest->step);
  else
    std::printf("target error %.3g: no run reaches it (every run failed)\n", target);
}

void plotWorkPrecision(const std::string& stem, const std::string& title, const std::vector<PrecisionRun>& runs,
                       const std::string& error_label) {
  PlotPanel panel{.xlabel = "wall time [s]", .ylabel = error_label, .log_y = true, .log_x = true};
  for (const PrecisionRun& run : runs) {
    auto series = std::find_if(panel.series.begin(), panel.series.end(),
                               [&](const PlotSeries& s) { return s.title == run.variant; });
    if (series == panel.series.end()) series = panel.series.insert(panel.series.end(), PlotSeries{run.variant, {}});
    if (!run.failed && run.error > 0.0 && run.seconds > 0.0) series->points.emplace_back(run.seconds, run.error);
  }
  std::erase_if(panel.series, [](const PlotSeries& s) { return s.points.empty(); });
  plotPanels(stem, title, {panel});
}

}  // namespace mbsopt
