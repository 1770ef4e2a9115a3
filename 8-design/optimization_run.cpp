#include "mbsopt/design/optimization_run.hpp"

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

#include "mbsopt/model/units.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/design/design_nlp.hpp"

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
    run.variable_units.push_back(parameterUnit(nlp.problem().scene.model, v.index));
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

std::string reportedPointName(const OptimizerResult& result) {
  return result.status == OptimizerStatus::Unsupported ? "start" : toString(result.reported);
}

}  // namespace mbsopt
