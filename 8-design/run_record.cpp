#include "mbsopt/design/run_record.hpp"

#include <cmath>

#include "mbsopt/design/provenance.hpp"

namespace mbsopt {

namespace {
nlohmann::json finiteOrNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); }
}  // namespace


const char* const kReportedPointRule =
    "final: the optimizer's final point, where its own convergence test passed, the point meets every constraint "
    "within its tolerance in the problem's own units and it passes the first-order check; otherwise cheapest_feasible: the point of least cost (the cost's own "
    "functional, not b_{k+1}) among its iterates (the history's records; NLopt's: every point it evaluated) that meet "
    "them, the latest of equals; least_infeasible where none "
    "does; start where the optimizer cannot take the problem and evaluated nothing";

nlohmann::json boundWorthJson(const std::vector<BoundWorth>& worth, const std::string& cost_unit) {
  nlohmann::json out = nlohmann::json::array();
  for (const BoundWorth& w : worth) {
    const char* kind = w.kind == BoundWorth::Kind::Constraint ? "constraint"
                       : w.kind == BoundWorth::Kind::LowerBound ? "lower_bound"
                                                                : "upper_bound";
    const std::string dotted = w.kind == BoundWorth::Kind::Constraint
                                   ? "design.constraints." + std::to_string(w.index) + (w.equality ? ".equals" : ".bound")
                                   : "design.variables." + std::to_string(w.index) +
                                         (w.kind == BoundWorth::Kind::LowerBound ? ".lower" : ".upper");
    out.push_back({{"name", w.name},
                   {"kind", kind},
                   {"parameter", dotted},
                   {"bound", w.bound},
                   {"unit", w.unit.empty() ? "SI" : w.unit},
                   {"equality", w.equality},
                   {"d_cost_d_bound", w.derivative},
                   {"relaxing_lowers_cost_by", w.relaxingLowersCostBy()},
                   {"relaxed_by", w.equality ? "neither" : w.raising_relaxes ? "raising" : "lowering"},
                   {"cost_unit_per_unit", cost_unit + " per " + (w.unit.empty() ? "SI unit" : w.unit)},
                   {"tolerance", w.tolerance}});
  }
  return out;
}

nlohmann::json verdictsJson(const std::vector<ConstraintVerdict>& verdicts) {
  nlohmann::json out = nlohmann::json::array();
  for (const ConstraintVerdict& v : verdicts)
    out.push_back({{"name", v.name}, {"unit", v.unit}, {"value", v.value}, {v.equality ? "equals" : "bound", v.bound},
                   {"excess", v.excess}, {"tolerance", v.tolerance}, {"met", v.met()}});
  return out;
}

nlohmann::json toJson(const OptimizationRun& run, const std::string& problem) {
  const OptimizerResult& r = run.result;
  nlohmann::json history = nlohmann::json::array();
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    const IterationRecord& h = r.history[k];
    history.push_back({{"iteration", h.iteration},
                       {"cost", h.cost},
                       {"max_violation", h.max_violation},
                       {"step", h.step},
                       {"cost_functional", run.iterate_costs[k]},
                       {"simulations", h.value_evaluations},
                       {"gradient_evaluations", h.gradient_evaluations},
                       {"simulation_equivalents", h.simulation_equivalents},
                       {"design", run.iterate_designs[k].empty() ? nlohmann::json(nullptr) : nlohmann::json(run.iterate_designs[k])}});
  }
  nlohmann::json variables = nlohmann::json::array();
  for (std::size_t i = 0; i < run.variables.size(); ++i) {
    const DesignVariable& v = run.variables[i];
    variables.push_back({{"parameter", v.parameter}, {"unit", run.variable_units[i]}, {"lower", v.lower},
                         {"upper", v.upper}, {"scale", v.scale}, {"start", run.start[i]}, {"final", run.design[i]}});
  }
  nlohmann::json settings = nlohmann::json::array();
  for (const std::string& setting : run.choice.settings) settings.push_back(setting);
  return {{"problem", problem},
          {"mbsopt_version", version()},
          {"command_line", commandLine()},
          {"variables", variables},
          {"variables_unit", "SI (m, kg, s, N, rad) of each parameter, variables[].unit its own"},
          {"artificial_variable", {{"start", run.artificial.initial}, {"lower", run.artificial.lower},
                                   {"upper", run.artificial.upper}, {"scale", run.artificial.scale},
                                   {"final", r.cost}}},
          {"budget", {{"simulation_equivalents", finiteOrNull(run.choice.budget.simulation_equivalents)},
                      {"wall_time_s", finiteOrNull(run.choice.budget.wall_time_s)},
                      {"gradient_cost", run.gradient_cost},
                      {"gradient_cost_source", run.gradient_cost_source},
                      {"spent", r.simulation_equivalents},
                      {"unit", "simulation-equivalents: one per simulation, gradient_cost per gradient"},
                      {"max_iterations", run.choice.max_iterations},
                      {"max_iterations_counts", "NLopt: objective evaluations; Ipopt and SDCC: their own iterations"}}},
          {"settings", settings},
          {"optimizer", run.choice.optimizer},
          {"gradient", run.choice.gradient},
          {"formulation", run.choice.formulation},
          {"epsilon", run.choice.epsilon.value_or(0.0)},
          {"status", toString(r.status)},
          {"message", r.message},
          {"design", run.design},
          {"responses", run.responses},
          {"response_units", run.response_units},
          {"constraints", verdictsJson(run.verdicts)},
          {"feasible", feasible(run)},
          {"initial_cost", run.initial_cost},
          {"cost", r.cost},
          {"cost_functional", {{"name", run.cost_response}, {"unit", run.cost_unit}, {"start", run.initial_cost},
                               {"final", run.responses[run.cost_response]}}},
          {"reported_iterate", {{"iteration", run.reported_iteration < 0 ? nlohmann::json(nullptr)
                                                                         : nlohmann::json(run.reported_iteration)},
                                {"point", reportedPointName(r)},
                                {"rule", kReportedPointRule},
                                {"cheapest_feasible_cost", finiteOrNull(run.cheapest_cost)},
                                {"cheapest_feasible_iteration", run.cheapest_iteration < 0 ? nlohmann::json(nullptr)
                                                                                           : nlohmann::json(run.cheapest_iteration)}}},
          {"bound_worth", boundWorthJson(run.bound_worth, run.cost_unit)},
          {"kkt_residual", r.first_order ? nlohmann::json(r.first_order->residual) : nlohmann::json(nullptr)},
          {"tolerance_worth", finiteOrNull(run.tolerance_worth)},
          {"max_violation", r.max_violation},
          {"iterations", r.iterations},
          {"simulations", r.value_evaluations},
          {"gradient_evaluations", r.gradient_evaluations},
          {"simulation_equivalents", r.simulation_equivalents},
          {"thread_time_simulations", run.thread_time_simulations},
          {"simulation_s", run.simulation_s},
          {"simulations_ahead", run.simulations_ahead},
          {"simulations_ahead_used", run.simulations_ahead_used},
          {"wall_time_s", r.wall_time_s},
          {"history", history}};
}

}  // namespace mbsopt
