#include "mbsopt/design/optimization_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mbsopt/model/units.hpp"

namespace mbsopt {

PlotPanel designPanel(const OptimizationRun& run) {
  PlotPanel panel{.xlabel = "iteration", .ylabel = "design variables (SI)", .log_y = true};
  for (std::size_t i = 0; i < run.variables.size(); ++i) {
    PlotSeries series{run.variable_units[i].empty() ? run.variables[i].parameter
                                                    : withUnit(run.variables[i].parameter, run.variable_units[i]),
                      {}};
    for (std::size_t k = 0; k < run.iterate_designs.size(); ++k)
      if (!run.iterate_designs[k].empty())
        series.points.emplace_back(run.result.history[k].iteration, run.iterate_designs[k][i]);
    panel.series.push_back(series);
  }
  return panel;
}

double distanceToBest(double cost, double best) {
  return std::max(std::abs(cost - best), kDistanceFloor * std::max(std::abs(best), 1e-300));
}

std::vector<PlotPanel> convergencePanels(const std::vector<std::pair<std::string, const OptimizationRun*>>& runs,
                                         bool against_simulation_equivalents, double reference) {
  const std::string x = against_simulation_equivalents ? "simulation-equivalents (simulations + gradients at their cost)" : "iteration";
  // The best: the reference where given, else the least reported cost among the feasible runs, else
  // the least cost any record has.
  double best = reference;
  const std::string source = std::isnan(reference) ? "the best reported" : "the reference";
  for (const bool feasible_only : {true, false})
    for (const auto& [title, run] : runs) {
      if (!std::isnan(reference)) break;
      if (feasible_only && feasible(*run)) best = std::min(std::isnan(best) ? INFINITY : best, run->responses[run->cost_response].get<double>());
      if (!feasible_only && std::isnan(best))
        for (double c : run->iterate_costs)
          if (!std::isnan(c)) best = std::min(std::isnan(best) ? INFINITY : best, c);
    }
  const OptimizationRun* first = runs.empty() ? nullptr : runs.front().second;
  char label[120], title[160];
  std::snprintf(label, sizeof label, "|%s - best| [%s]", first ? first->cost_response.c_str() : "cost",
                first ? first->cost_unit.c_str() : "SI");
  std::snprintf(title, sizeof title, "best %.8g (%s; 0 drawn at %.0e of it)", best, source.c_str(), kDistanceFloor);
  PlotPanel cost{.xlabel = x, .ylabel = label, .log_y = true, .title = title};
  PlotPanel violation{.xlabel = x, .ylabel = "max violation (0 drawn at 1e-12)", .log_y = true};
  double start = 0.0;  // the farthest start: excursions above it are cut off, not to flatten the rest
  std::vector<PlotSeries> reported_costs, reported_violations;  // each run's reported point, ringed in its colour
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& [title, run] = runs[i];
    PlotSeries c{title, {}}, v{title, {}};
    PlotSeries reported_c{"", {}, true, static_cast<int>(i) + 1}, reported_v = reported_c;
    for (std::size_t k = 0; k < run->result.history.size(); ++k) {
      const IterationRecord& h = run->result.history[k];
      const double at = against_simulation_equivalents ? h.simulation_equivalents : h.iteration;
      const double violation_at = std::max(h.max_violation, 1e-12);
      if (!std::isnan(run->iterate_costs[k])) c.points.emplace_back(at, distanceToBest(run->iterate_costs[k], best));
      v.points.emplace_back(at, violation_at);
      if (h.iteration == run->reported_iteration && !std::isnan(run->iterate_costs[k])) {
        reported_c.points = {{at, distanceToBest(run->iterate_costs[k], best)}};
        reported_v.points = {{at, violation_at}};
      }
    }
    start = std::max(start, distanceToBest(run->initial_cost, best));
    cost.series.push_back(c);
    violation.series.push_back(v);
    reported_costs.push_back(reported_c);
    reported_violations.push_back(reported_v);
  }
  cost.series.insert(cost.series.end(), reported_costs.begin(), reported_costs.end());
  violation.series.insert(violation.series.end(), reported_violations.begin(), reported_violations.end());
  if (start > 0.0) cost.y_max = 2.0 * start;
  return {cost, violation};
}

}  // namespace mbsopt
