#include "app/optimization_run.hpp"

#include "app/command_line.hpp"

#include <algorithm>
#include <limits>
#include <numbers>
#include <optional>
#include <variant>

#include "problems/design_nlp.hpp"
#include "sensitivity/design_evaluation.hpp"
#include "sensitivity/gradient_method.hpp"

namespace mbsopt {

namespace {

/// The transcription measures in the order of formulationNames().
constexpr TimeMeasure kFormulationMeasures[] = {TimeMeasure::PositivePart, TimeMeasure::SquaredPositivePart,
                                                TimeMeasure::KsAggregate, TimeMeasure::GridMax};

TimeMeasure formulationMeasure(const std::string& name) {
  const auto& names = formulationNames();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return kFormulationMeasures[i];
  throw std::invalid_argument("unknown formulation '" + name + "'");
}

std::string formulationName(TimeMeasure measure) {
  for (std::size_t i = 0; i < formulationNames().size(); ++i)
    if (kFormulationMeasures[i] == measure) return formulationNames()[i];
  throw std::invalid_argument("the problem's transcription is not one of the formulations");
}

/// The key of a sensor's response: `max_abs_NAME`, or `max_abs_NAME_deg` for angles (in degrees).
std::string responseKey(const Sensor& sensor) { return "max_abs_" + sensor.name + (isAngle(sensor) ? "_deg" : ""); }

/// The exact functional of an integral, RMS or final-value measure; none for an extreme.
std::optional<TimeMeasure> exactMeasure(ResponseMeasure of) {
  if (of == ResponseMeasure::Integral) return TimeMeasure::Integral;
  if (of == ResponseMeasure::Rms) return TimeMeasure::RootMeanSquare;
  if (of == ResponseMeasure::FinalValue) return TimeMeasure::FinalValue;
  return std::nullopt;
}

/// The key of a sensor's exact functional: `integral_NAME`, `rms_NAME` or `final_NAME` (`_deg` for angles).
std::string functionalKey(const Sensor& sensor, TimeMeasure measure) {
  const char* prefix = measure == TimeMeasure::Integral ? "integral_" : measure == TimeMeasure::RootMeanSquare ? "rms_" : "final_";
  return prefix + sensor.name + (isAngle(sensor) ? "_deg" : "");
}

/// The key of the cost's own functional: its sensor's responseKey for an extreme, functionalKey for
/// an exact cost.
std::string costKey(const DesignProblem& problem) {
  const ResponseCost& cost = problem.design.cost;
  const Sensor& sensor = problem.scene.model.sensors()[static_cast<std::size_t>(sensorIndex(problem.scene.model, cost.sensor))];
  const std::optional<TimeMeasure> exact = exactMeasure(cost.of);
  return exact ? functionalKey(sensor, *exact) : responseKey(sensor);
}

/// max |y| over the time grid of every sensor the cost and the constraints use, and the value of each
/// exact functional the cost or a constraint takes (functionalKey), on one trajectory.
nlohmann::json trajectoryResponses(const DesignNlp& nlp, const Trajectory& trajectory) {
  const DesignProblem& problem = nlp.problem();
  const Model& model = problem.scene.model;
  nlohmann::json out = nlohmann::json::object();
  for (const ConstraintFunctional& f : nlp.functionals()) {
    const Sensor& sensor = model.sensors()[static_cast<std::size_t>(f.sensor)];
    out[responseKey(sensor)] = inUnits(sensor, trajectory.sensors.col(f.sensor).cwiseAbs().maxCoeff());
  }
  const auto addExact = [&](const std::string& name, ResponseMeasure of) {
    const std::optional<TimeMeasure> exact = exactMeasure(of);
    if (!exact) return;
    const int index = sensorIndex(model, name);
    const Sensor& sensor = model.sensors()[static_cast<std::size_t>(index)];
    out[functionalKey(sensor, *exact)] =
        inUnits(sensor, evaluateTimeFunctional(*exact, trajectory.time, trajectory.sensors.col(index)).value);
  };
  addExact(problem.design.cost.sensor, problem.design.cost.of);
  for (const ResponseConstraint& c : problem.design.constraints) addExact(c.sensor, c.of);
  return out;
}

/// trajectoryResponses of the response; with load cases, each case's under KEY_CASE and, under KEY,
/// the largest over the cases (the worst case, which the cost's epigraph bounds).
nlohmann::json responses(const DesignNlp& nlp, const DesignResponse& response) {
  const std::vector<LoadCase>& cases = nlp.problem().load_cases;
  if (cases.empty()) return trajectoryResponses(nlp, response.trajectory);
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const nlohmann::json own = trajectoryResponses(nlp, caseTrajectory(response, c));
    for (const auto& [key, value] : own.items()) {
      out[key + "_" + cases[c].name] = value;
      out[key] = out.contains(key) ? std::max(out[key].get<double>(), value.get<double>()) : value.get<double>();
    }
  }
  return out;
}

/// The design variables of the scaled x in SI units, without b_{k+1}.
std::vector<double> designInSi(const DesignProblem& problem, const Eigen::VectorXd& x) {
  std::vector<double> design;
  const auto& variables = problem.design.variables;
  for (std::size_t i = 0; i < variables.size(); ++i) design.push_back(x[static_cast<Eigen::Index>(i)] * variables[i].scale);
  return design;
}

}  // namespace

const std::vector<std::string>& formulationNames() {
  static const std::vector<std::string> names{"positive_part", "squared_positive_part", "ks", "grid_max"};
  return names;
}

OptimizationRun runOptimization(DesignProblem problem, const RunChoice& choice,
                                const std::function<void(const IterationRecord&)>& on_iteration,
                                std::shared_ptr<ThreadBudget> shared_threads) {
  OptimizationRun run;
  run.choice = choice;
  if (!choice.formulation.empty()) problem.design.transcription.measure = formulationMeasure(choice.formulation);
  if (choice.epsilon) problem.design.transcription.tolerance = *choice.epsilon;
  run.choice.formulation = formulationName(problem.design.transcription.measure);
  run.choice.epsilon = problem.design.transcription.tolerance;
  if (run.choice.gradient == "fd") run.choice.gradient = "fd_central";
  DesignNlp nlp(std::move(problem), run.choice.gradient, 1e-6, choice.gradient_jobs, std::move(shared_threads));
  OptimizerOptions options;
  options.max_iterations = choice.max_iterations;
  options.on_iteration = on_iteration;
  for (const std::string& setting : choice.settings) {
    const std::size_t equals = setting.find('=');
    if (equals == std::string::npos || equals == 0)
      throw std::invalid_argument("--setting " + setting + ": expected [OPTIMIZER.]NAME=VALUE");
    std::string name = setting.substr(0, equals);
    if (const std::size_t dot = name.find('.'); dot != std::string::npos) {  // meant for one optimizer
      const std::string optimizer = name.substr(0, dot);
      const auto& known = optimizerNames();
      if (std::find(known.begin(), known.end(), optimizer) == known.end())
        throw std::invalid_argument("--setting " + setting + ": '" + optimizer + "' is not an optimizer");
      if (optimizer != choice.optimizer) continue;
      name = name.substr(dot + 1);
    }
    options.settings.emplace_back(name, setting.substr(equals + 1));
  }
  run.result = minimize(choice.optimizer, nlp, options);
  run.variables = nlp.problem().design.variables;
  run.artificial = nlp.problem().design.artificial;
  run.start = designInSi(nlp.problem(), nlp.start());
  if (run.result.x.size() == 0) run.result.x = nlp.start();  // nothing was evaluated (its error follows below)
  run.design = designInSi(nlp.problem(), run.result.x);
  for (std::size_t k = 0; k < run.result.history.size(); ++k)
    if (run.result.history[k].x.size() == run.result.x.size() && run.result.history[k].x == run.result.x)
      run.reported_iteration = run.result.history[k].iteration;
  for (const IterationRecord& h : run.result.history)
    run.iterate_designs.push_back(h.x.size() > 0 ? designInSi(nlp.problem(), h.x) : std::vector<double>{});
  // The points the run knows are not simulated again; copies, as a new simulation may push one out.
  const DesignResponse initial = nlp.simulation(nlp.start());
  const DesignResponse final = nlp.simulation(run.result.x);
  run.simulation_s = nlp.simulationSeconds();  // the fastest: interference only ever slows a run down
  run.simulation_equivalents = nlp.evaluationThreadSeconds() / run.simulation_s;
  run.simulations_ahead = nlp.simulationsAhead();
  run.simulations_ahead_used = nlp.simulationsAheadUsed();
  run.responses = responses(nlp, final);
  run.verdicts = constraintVerdicts(nlp.problem(), final);
  const int cost_sensor = nlp.functionals()[0].sensor;  // the cost's constraints come first
  run.cost_response = costKey(nlp.problem());
  run.cost_sensor = nlp.problem().design.cost.sensor;
  run.initial_cost = responses(nlp, initial)[run.cost_response].get<double>();
  // The cost's history in the load case where the final design's cost is largest (the only one without cases).
  std::size_t worst = 0;
  for (std::size_t c = 1; c < nlp.problem().load_cases.size(); ++c) {
    const std::string& name = nlp.problem().load_cases[c].name;
    const std::string& worst_name = nlp.problem().load_cases[worst].name;
    if (run.responses[run.cost_response + "_" + name].get<double>() > run.responses[run.cost_response + "_" + worst_name].get<double>())
      worst = c;
  }
  run.time = caseTrajectory(final, worst).time;
  run.initial_history = caseTrajectory(initial, worst).sensors.col(cost_sensor);
  run.final_history = caseTrajectory(final, worst).sensors.col(cost_sensor);
  return run;
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
                       {"simulations", h.value_evaluations},
                       {"gradient_evaluations", h.gradient_evaluations},
                       {"design", run.iterate_designs[k].empty() ? nlohmann::json(nullptr) : nlohmann::json(run.iterate_designs[k])}});
  }
  nlohmann::json variables = nlohmann::json::array();
  for (std::size_t i = 0; i < run.variables.size(); ++i) {
    const DesignVariable& v = run.variables[i];
    variables.push_back({{"parameter", v.parameter}, {"lower", v.lower}, {"upper", v.upper}, {"scale", v.scale},
                         {"start", run.start[i]}, {"final", run.design[i]}});
  }
  nlohmann::json settings = nlohmann::json::array();
  for (const std::string& setting : run.choice.settings) settings.push_back(setting);
  return {{"problem", problem},
          {"mbsopt_version", MBSOPT_VERSION},
          {"command_line", commandLine()},
          {"variables", variables},
          {"artificial_variable", {{"start", run.artificial.initial}, {"lower", run.artificial.lower},
                                   {"upper", run.artificial.upper}, {"scale", run.artificial.scale},
                                   {"final", r.cost}}},
          {"budget", {{"max_iterations", run.choice.max_iterations},
                      {"counts", "NLopt: objective evaluations; Ipopt and SDCC: their own iterations"}}},
          {"settings", settings},
          {"optimizer", run.choice.optimizer},
          {"gradient", run.choice.gradient},
          {"formulation", run.choice.formulation},
          {"epsilon", run.choice.epsilon.value_or(0.0)},
          {"status", toString(r.status)},
          {"message", r.message},
          {"design", run.design},
          {"responses", run.responses},
          {"constraints", verdictsJson(run.verdicts)},
          {"feasible", feasible(run)},
          {"initial_cost", run.initial_cost},
          {"cost", r.cost},
          {"cost_functional", {{"name", run.cost_response}, {"start", run.initial_cost},
                               {"final", run.responses[run.cost_response]}}},
          {"reported_iterate", {{"iteration", run.reported_iteration < 0 ? nlohmann::json(nullptr)
                                                                         : nlohmann::json(run.reported_iteration)},
                                {"rule", "the best point evaluated: feasible first, then the lowest b_{k+1}"}}},
          {"max_violation", r.max_violation},
          {"iterations", r.iterations},
          {"simulations", r.value_evaluations},
          {"gradient_evaluations", r.gradient_evaluations},
          {"simulation_equivalents", run.simulation_equivalents},
          {"simulation_s", run.simulation_s},
          {"simulations_ahead", run.simulations_ahead},
          {"simulations_ahead_used", run.simulations_ahead_used},
          {"wall_time_s", r.wall_time_s},
          {"history", history}};
}

void addSettingOption(CLI::App& command, std::vector<std::string>& settings) {
  command.add_option("--setting", settings,
                     "An optimizer's own setting, NAME=VALUE for every optimizer that runs or OPTIMIZER.NAME=VALUE "
                     "for one (ipopt.mu_strategy=adaptive); repeat for several. sdcc: active_set_epsilon, "
                     "initial_step_bound, shrink_factor, growth_factor, growth_ratio, acceptance_ratio, "
                     "min_step_bound, stationarity_tolerance, initial_penalty, penalty_factor, weights (one per "
                     "variable, comma-separated) (optimizers/sdcc.hpp); ipopt: any Ipopt option, e.g. "
                     "mu_strategy=adaptive or tol=1e-10; slsqp, mma, ccsaq: NLopt's stopping criteria xtol_rel "
                     "(default 1e-6), xtol_abs, ftol_rel (default 0: NLopt applies it at infeasible points too, where "
                     "b_{k+1} stays put while feasibility is restored), ftol_abs, stopval, maxtime [s]; mma, ccsaq "
                     "also inner_maxeval, dual_ftol_rel, verbosity. An unknown name is an error")
      ->allow_extra_args(false);
}

std::vector<std::string> gradientChoices() {
  std::vector<std::string> choices = gradientMethodNames();
  choices.push_back("fd");
  return choices;
}

PlotPanel designPanel(const OptimizationRun& run) {
  PlotPanel panel{.xlabel = "iteration", .ylabel = "design variables (SI)", .log_y = true};
  for (std::size_t i = 0; i < run.variables.size(); ++i) {
    PlotSeries series{run.variables[i].parameter, {}};
    for (std::size_t k = 0; k < run.iterate_designs.size(); ++k)
      if (!run.iterate_designs[k].empty())
        series.points.emplace_back(run.result.history[k].iteration, run.iterate_designs[k][i]);
    panel.series.push_back(series);
  }
  return panel;
}

std::vector<PlotPanel> convergencePanels(const std::vector<std::pair<std::string, const OptimizationRun*>>& runs,
                                         bool against_simulations) {
  const std::string x = against_simulations ? "simulations" : "iteration";
  PlotPanel cost{.xlabel = x, .ylabel = "cost"};
  PlotPanel violation{.xlabel = x, .ylabel = "max violation (0 drawn at 1e-12)", .log_y = true};
  for (const auto& [title, run] : runs) {
    PlotSeries c{title, {}}, v{title, {}};
    for (const IterationRecord& h : run->result.history) {
      const double at = against_simulations ? static_cast<double>(h.value_evaluations) : h.iteration;
      c.points.emplace_back(at, h.cost);
      v.points.emplace_back(at, std::max(h.max_violation, 1e-12));
    }
    cost.series.push_back(c);
    violation.series.push_back(v);
  }
  return {cost, violation};
}

}  // namespace mbsopt
