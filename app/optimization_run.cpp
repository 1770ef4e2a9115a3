#include "app/option_checks.hpp"
#include "app/optimization_run.hpp"

#include "app/command_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <variant>

#include "mbsopt/dynamics/units.hpp"
#include "mbsopt/problems/design_nlp.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"

namespace mbsopt {

namespace {

/// Four significant digits, for messages.
std::string shortNumber(double value) {
  std::ostringstream out;
  out << std::setprecision(4) << value;
  return out.str();
}

/// The key of a sensor's response: `max_abs_NAME`, or `max_abs_NAME_deg` for angles (in degrees).
std::string responseKey(const Sensor& sensor) { return "max_abs_" + sensor.name + (isAngle(sensor) ? "_deg" : ""); }

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
/// exact functional the cost or a constraint takes (functionalKey), on one trajectory; the unit of
/// each into `units` under the same key.
nlohmann::json trajectoryResponses(const DesignNlp& nlp, const Trajectory& trajectory, nlohmann::json& units) {
  const DesignProblem& problem = nlp.problem();
  const Model& model = problem.scene.model;
  nlohmann::json out = nlohmann::json::object();
  for (const ConstraintFunctional& f : nlp.functionals()) {
    const Sensor& sensor = model.sensors()[static_cast<std::size_t>(f.sensor)];
    out[responseKey(sensor)] = inUnits(sensor, trajectory.sensors.col(f.sensor).cwiseAbs().maxCoeff());
    units[responseKey(sensor)] = sensorUnit(model, sensor);
  }
  const auto addExact = [&](const std::string& name, ResponseMeasure of) {
    const std::optional<TimeMeasure> exact = exactMeasure(of);
    if (!exact) return;
    const int index = sensorIndex(model, name);
    const Sensor& sensor = model.sensors()[static_cast<std::size_t>(index)];
    out[functionalKey(sensor, *exact)] =
        inUnits(sensor, evaluateTimeFunctional(*exact, trajectory.time, trajectory.sensors.col(index)).value);
    units[functionalKey(sensor, *exact)] = measureUnit(model, sensor, of);
  };
  addExact(problem.design.cost.sensor, problem.design.cost.of);
  for (const ResponseConstraint& c : problem.design.constraints) addExact(c.sensor, c.of);
  return out;
}

/// trajectoryResponses of the response; with load cases, each case's under KEY_CASE and, under KEY,
/// the largest over the cases (the worst case, which the cost's epigraph bounds).
nlohmann::json responses(const DesignNlp& nlp, const DesignResponse& response, nlohmann::json& units) {
  const std::vector<LoadCase>& cases = nlp.problem().load_cases;
  if (cases.empty()) return trajectoryResponses(nlp, caseTrajectory(response, 0), units);
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const nlohmann::json own = trajectoryResponses(nlp, caseTrajectory(response, c), units);
    for (const auto& [key, value] : own.items()) {
      units[key + "_" + cases[c].name] = units[key];
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

RunChoice resolvedChoice(const DesignProblem& problem, RunChoice choice) {
  if (choice.formulation.empty()) choice.formulation = formulationOf(problem.design.transcription.measure).name;
  else formulation(choice.formulation);  // an unknown name throws
  if (!choice.epsilon) choice.epsilon = problem.design.transcription.tolerance;
  choice.gradient = gradientMethod(choice.gradient).name;  // an alias (fd) becomes the name it stands for
  return choice;
}

DesignProblem formulatedProblem(DesignProblem problem, const RunChoice& resolved) {
  problem.design.transcription.measure = formulation(resolved.formulation).measure;
  problem.design.transcription.tolerance = *resolved.epsilon;
  return problem;
}

void addSweepOptions(CLI::App& command, SweepAxes& axes, RunChoice& shared) {
  command.add_option("--optimizers", axes.optimizers, "Optimizers to run")
      ->delimiter(',')
      ->check(CLI::IsMember(optimizerNames()))
      ->capture_default_str();
  command.add_option("--gradients", axes.gradients, "Gradient methods (fd = fd_central)")
      ->delimiter(',')
      ->check(CLI::IsMember(gradientMethodChoices()))
      ->capture_default_str();
  command.add_option("--formulations", axes.formulations,
                     "Formulations (see `mbsopt optimize --help`); default: each problem's own")
      ->delimiter(',')
      ->check(CLI::IsMember(formulationNames()));
  command
      .add_option_function<double>(
          "--epsilon", [&shared](double epsilon) { shared.epsilon = epsilon; },
          "ε ≥ 0 of every run, with the problem's measure or each of --formulations (see `mbsopt optimize --help`); "
          "default: each problem's own")
      ->check(nonNegativeNumber());
}

std::vector<RunChoice> sweepChoices(const SweepAxes& axes, const RunChoice& shared) {
  std::vector<RunChoice> choices;
  for (const std::string& formulation : axes.formulations)
    for (const std::string& gradient : axes.gradients)
      for (const std::string& optimizer : axes.optimizers) {
        RunChoice choice = shared;
        choice.optimizer = optimizer;
        choice.gradient = gradient;
        choice.formulation = formulation;
        choices.push_back(choice);
      }
  return choices;
}

std::string formulationLabel(const RunChoice& c) {
  std::string label = c.formulation.empty() ? "problem's formulation" : c.formulation;
  if (c.epsilon.value_or(0.0) > 0.0) {
    char epsilon[32];
    std::snprintf(epsilon, sizeof epsilon, " ε=%g", *c.epsilon);
    label += epsilon;
  }
  return label;
}

std::string runLabel(const RunChoice& c) { return c.optimizer + "/" + c.gradient + "/" + formulationLabel(c); }

std::string runFileStem(const RunChoice& c) {
  std::string name = c.optimizer + "-" + c.gradient + "-" + c.formulation;
  if (c.epsilon.value_or(0.0) > 0.0) {
    char epsilon[32];
    std::snprintf(epsilon, sizeof epsilon, "-eps%g", *c.epsilon);
    name += epsilon;
  }
  return name;
}

namespace {

/// The limits and numbers of a choice, refused as the command line refuses them (app/option_checks.hpp),
/// for the callers that do not come through it (the Python module, C++): a budget may be infinite.
void checkRunChoice(const RunChoice& choice) {
  const auto refuse = [](const std::string& name, const std::string& what, double value) {
    throw std::invalid_argument(name + " must be " + what + ", got " + shortNumber(value));
  };
  if (choice.max_iterations < 1) refuse("max_iter", "a positive integer", choice.max_iterations);
  if (!(choice.budget.simulation_equivalents > 0.0))
    refuse("budget", "a positive number of simulation-equivalents", choice.budget.simulation_equivalents);
  if (!(choice.budget.wall_time_s > 0.0)) refuse("wall_time", "a positive time in seconds", choice.budget.wall_time_s);
  if (choice.gradient_cost && !(std::isfinite(*choice.gradient_cost) && *choice.gradient_cost > 0.0))
    refuse("gradient_cost", "a positive finite number", *choice.gradient_cost);
  if (choice.epsilon && !(std::isfinite(*choice.epsilon) && *choice.epsilon >= 0.0))
    refuse("epsilon", "a finite number >= 0", *choice.epsilon);
  if (choice.gradient_jobs < 1) refuse("jobs", "a positive integer", choice.gradient_jobs);
}

}  // namespace

OptimizationRun runOptimization(DesignProblem problem, const RunChoice& choice,
                                const std::function<void(const IterationRecord&)>& on_iteration,
                                std::shared_ptr<ThreadBudget> shared_threads) {
  checkRunChoice(choice);
  OptimizationRun run;
  run.choice = resolvedChoice(problem, choice);
  DesignNlp nlp(formulatedProblem(std::move(problem), run.choice), run.choice.gradient, 1e-6, choice.gradient_jobs, std::move(shared_threads));
  if (choice.gradient_cost) {
    nlp.setGradientCost(*choice.gradient_cost);
    run.gradient_cost_source = "given";
  } else if (gradientMethod(run.choice.gradient).simulations_per_variable > 0) {
    run.gradient_cost_source = "counted";
  } else {
    try {
      nlp.setGradientCost(nlp.measureGradientCost(nlp.start()));
      run.gradient_cost_source = "measured";
    } catch (const std::exception&) {  // the start cannot be simulated: the run itself says so below
      run.gradient_cost_source = "not measured (the start could not be evaluated)";
    }
  }
  run.gradient_cost = nlp.gradientCost();
  OptimizerOptions options;
  options.max_iterations = choice.max_iterations;
  options.budget = choice.budget;
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
  for (const DesignVariable& v : run.variables)
    run.variable_units.push_back(parameterUnit(nlp.problem().scene.model, nlp.problem().scene.model.parameterIndex(v.parameter)));
  run.artificial = nlp.problem().design.artificial;
  run.start = designInSi(nlp.problem(), nlp.start());
  if (run.result.x.size() == 0) run.result.x = nlp.start();  // nothing was evaluated (its error follows below)
  run.design = designInSi(nlp.problem(), run.result.x);
  const auto recordOf = [&](const Eigen::VectorXd& x) {
    int found = -1;
    for (const IterationRecord& h : run.result.history)
      if (h.x.size() == x.size() && h.x == x) found = h.iteration;
    return found;
  };
  run.reported_iteration = recordOf(run.result.x);
  for (const IterationRecord& h : run.result.history)
    run.iterate_designs.push_back(h.x.size() > 0 ? designInSi(nlp.problem(), h.x) : std::vector<double>{});
  // The points the run knows are not simulated again; copies, as a new simulation may push one out.
  const DesignResponse initial = nlp.simulation(nlp.start());
  const DesignResponse final = nlp.simulation(run.result.x);
  run.simulation_s = nlp.simulationSeconds();  // the fastest: interference only ever slows a run down
  run.thread_time_simulations = nlp.evaluationThreadSeconds() / run.simulation_s;
  run.simulations_ahead = nlp.simulationsAhead();
  run.simulations_ahead_used = nlp.simulationsAheadUsed();
  run.response_units = nlohmann::json::object();
  run.responses = responses(nlp, final, run.response_units);
  run.verdicts = constraintVerdicts(nlp.problem(), final);
  if (run.result.status == OptimizerStatus::Converged && run.result.first_order) {
    run.bound_worth = boundWorth(nlp.problem(), nlp.functionals(), final, run.result.first_order->multipliers);
    run.tolerance_worth = toleranceWorth(run.bound_worth);
  }
  const int cost_sensor = nlp.functionals()[0].sensor;  // the cost's constraints come first
  run.cost_response = costKey(nlp.problem());
  run.cost_sensor = nlp.problem().design.cost.sensor;
  nlohmann::json units;
  run.initial_cost = responses(nlp, initial, units)[run.cost_response].get<double>();
  const Model& model = nlp.problem().scene.model;
  const Sensor& sensor = model.sensors()[static_cast<std::size_t>(cost_sensor)];
  run.cost_unit = measureUnit(model, sensor, nlp.problem().design.cost.of);
  run.cost_sensor_unit = sensorSiUnit(model, sensor);
  for (const IterationRecord& h : run.result.history) run.iterate_costs.push_back(inUnits(sensor, h.reported_cost));
  if (run.result.cheapest_x.size() > 0 && run.result.cheapest_x != run.result.x) {
    run.cheapest_cost = inUnits(sensor, run.result.cheapest_cost);
    run.cheapest_iteration = recordOf(run.result.cheapest_x);
  }
  // An algorithm's own convergence test knows only the transcription: where it passed at a point that
  // breaks a constraint in its own units, the run failed (EvaluationCache::conclude), and says which.
  const Eigen::VectorXd& final_point = run.result.final_point;
  if (run.result.status == OptimizerStatus::Failed && final_point.size() == run.result.x.size() &&
      final_point != run.result.x) {
    const std::vector<ConstraintVerdict> at_final = constraintVerdicts(nlp.problem(), nlp.simulation(final_point));
    const auto unmet = std::find_if(at_final.begin(), at_final.end(), [](const ConstraintVerdict& v) { return !v.met(); });
    if (unmet != at_final.end()) {
      std::ostringstream why;
      why << ": there " << unmet->name << " = " << std::setprecision(8) << unmet->value << ' ' << unmet->unit << " is "
          << shortNumber(unmet->excess) << " beyond its " << (unmet->equality ? "target " : "bound ")
          << shortNumber(unmet->bound) << ", more than its tolerance " << shortNumber(unmet->tolerance)
          << " (the formulation's transcription is not the constraint)";
      run.result.message += why.str();
    }
  }
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

namespace {
nlohmann::json finiteOrNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); }
}  // namespace

void measureGradientCosts(const DesignProblem& problem, std::vector<RunChoice>& choices) {
  std::map<std::string, std::optional<double>> measured;  // empty where the start cannot be simulated
  for (RunChoice& choice : choices) {
    const GradientMethodInfo& info = gradientMethod(choice.gradient);
    const std::string& method = info.name;
    if (choice.gradient_cost || info.simulations_per_variable > 0) continue;
    if (!measured.contains(method)) {
      const DesignNlp nlp(problem, method, 1e-6, choice.gradient_jobs);
      try {
        measured[method] = nlp.measureGradientCost(nlp.start());
      } catch (const std::exception&) {  // each run says so; measured once, not once per run
        measured[method] = std::nullopt;
      }
    }
    choice.gradient_cost = measured[method];
  }
}

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
          {"mbsopt_version", MBSOPT_VERSION},
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

std::string reportedPointName(const OptimizerResult& result) {
  return result.status == OptimizerStatus::Unsupported ? "start" : toString(result.reported);
}

void addBudgetOptions(CLI::App& command, RunChoice& choice) {
  command.add_option("--budget", choice.budget.simulation_equivalents,
                     "The budget of each run in simulation-equivalents, alike for every optimizer: a simulation "
                     "counts 1, a gradient --gradient-cost; an evaluation that would exceed it is not made, and the "
                     "run ends with its best point, status max_iterations (default: none)")
      ->check(positiveNumber());
  command.add_option("--wall-time", choice.budget.wall_time_s,
                     "The wall time of each run's optimizer [s]: no evaluation starts after it (default: none)")
      ->check(positiveNumber());
  command
      .add_option_function<double>(
          "--gradient-cost", [&choice](double cost) { choice.gradient_cost = cost; },
          "What one gradient counts in simulation-equivalents (default: for finite differences their simulations, "
          "one per design variable or two with fd_central; for an exact method the median of three timed "
          "gradient/simulation pairs on one thread at the start with b_{k+1} = 0, where the whole backward sweep runs)")
      ->check(positiveNumber());
  command.add_option("--max-iter", choice.max_iterations,
                     "Each optimizer's own limit (NLopt: objective evaluations; Ipopt and SDCC: their own "
                     "iterations); --budget is the one that counts alike for all")
      ->check(positiveInteger())
      ->capture_default_str();
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
