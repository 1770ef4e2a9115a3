#include "app/optimize_command.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <variant>

#include "app/atomic_file.hpp"
#include "app/scene_argument.hpp"
#include "optimizers/optimizer.hpp"
#include "sensitivity/design_evaluation.hpp"
#include "sensitivity/design_nlp.hpp"
#include "sensitivity/gradient_method.hpp"

namespace mbsopt {

namespace {

struct OptimizeOptions {
  SceneArgument problem;
  std::string optimizer = "slsqp";
  std::string gradient = "adjoint";
  std::string formulation = "positive_part";
  double tolerance = 0.0;
  int max_iterations = 100;
  std::string json;
};

/// The transcription measure of a --formulation name.
TimeMeasure formulationMeasure(const std::string& name) {
  if (name == "positive_part") return TimeMeasure::PositivePart;
  if (name == "squared_positive_part") return TimeMeasure::SquaredPositivePart;
  if (name == "ks") return TimeMeasure::KsAggregate;
  return TimeMeasure::GridMax;  // CLI11 has checked the name
}

bool isAngle(const Sensor& sensor) { return std::holds_alternative<RelativeAngleSensor>(sensor.kind); }

/// max |y| over the time grid of every sensor the cost and the constraints use, at the scaled x:
/// `max_abs_NAME` in SI units, angles as `max_abs_NAME_deg` in degrees.
nlohmann::json responses(const DesignNlp& nlp, const Eigen::VectorXd& x) {
  const DesignResponse response = evaluateDesign(nlp.problem(), nlp.functionals(), x);
  const auto& sensors = nlp.problem().scene.model.sensors();
  nlohmann::json out = nlohmann::json::object();
  for (const ConstraintFunctional& f : nlp.functionals()) {
    const Sensor& sensor = sensors[static_cast<std::size_t>(f.sensor)];
    const double largest = response.sensors.col(f.sensor).cwiseAbs().maxCoeff();
    if (isAngle(sensor))
      out["max_abs_" + sensor.name + "_deg"] = largest * 180.0 / std::numbers::pi;
    else
      out["max_abs_" + sensor.name] = largest;
  }
  return out;
}

void printIteration(const IterationRecord& r) {
  std::printf("%5d  %14.8e  %11.3e  %10.3e  %6ld  %6ld\n", r.iteration, r.cost, r.max_violation, r.step,
              r.value_evaluations, r.gradient_evaluations);
  std::fflush(stdout);
}

void optimize(const OptimizeOptions& options) {
  const SceneSource source = resolveScene(options.problem.scene);
  DesignProblem problem = loadDesignProblem(source, parseOverrides(source, options.problem.sets));
  problem.design.transcription.measure = formulationMeasure(options.formulation);
  problem.design.transcription.tolerance = options.tolerance;
  const std::string gradient = options.gradient == "fd" ? "fd_central" : options.gradient;
  DesignNlp nlp(std::move(problem), gradient);

  OptimizerOptions settings;
  settings.max_iterations = options.max_iterations;
  settings.on_iteration = printIteration;
  std::printf("optimize %s with %s, %s gradients, %s formulation: %lld variables, %lld constraints\n",
              source.path.c_str(), options.optimizer.c_str(), gradient.c_str(), options.formulation.c_str(),
              static_cast<long long>(nlp.variableCount()), static_cast<long long>(nlp.inequalityCount()));
  std::printf(" iter  cost            max_viol     step        sims   grads\n");
  const OptimizerResult result = minimize(options.optimizer, nlp, settings);

  const auto& variables = nlp.problem().design.variables;
  std::vector<double> design;
  for (std::size_t i = 0; i < variables.size(); ++i) design.push_back(result.x[static_cast<Eigen::Index>(i)] * variables[i].scale);
  std::printf("%s: %s (%s)\n", result.optimizer.c_str(), toString(result.status).c_str(), result.message.c_str());
  std::printf("cost %.8g, max violation %.3g, %d iterations, %ld simulations, %ld gradients, %.3g s\n", result.cost,
              result.max_violation, result.iterations, result.value_evaluations, result.gradient_evaluations,
              result.wall_time_s);
  for (std::size_t i = 0; i < variables.size(); ++i) std::printf("  %s = %.8g\n", variables[i].parameter.c_str(), design[i]);
  const nlohmann::json final_responses = responses(nlp, result.x);
  for (const auto& [name, value] : final_responses.items()) std::printf("  %s = %.6g\n", name.c_str(), value.get<double>());

  if (options.json.empty()) return;
  nlohmann::json history = nlohmann::json::array();
  for (const IterationRecord& r : result.history)
    history.push_back({{"iteration", r.iteration},
                       {"cost", r.cost},
                       {"max_violation", r.max_violation},
                       {"step", r.step},
                       {"simulations", r.value_evaluations},
                       {"gradient_evaluations", r.gradient_evaluations}});
  const nlohmann::json document = {{"problem", source.path},
                                   {"optimizer", options.optimizer},
                                   {"gradient", gradient},
                                   {"formulation", options.formulation},
                                   {"status", toString(result.status)},
                                   {"message", result.message},
                                   {"design", design},
                                   {"responses", final_responses},
                                   {"cost", result.cost},
                                   {"max_violation", result.max_violation},
                                   {"iterations", result.iterations},
                                   {"simulations", result.value_evaluations},
                                   {"gradient_evaluations", result.gradient_evaluations},
                                   {"wall_time_s", result.wall_time_s},
                                   {"history", history}};
  writeAtomically(options.json, [&](std::ostream& out) { out << document.dump(2) << '\n'; });
}

}  // namespace

void registerOptimizeCommand(CLI::App& app) {
  auto options = std::make_shared<OptimizeOptions>();
  CLI::App* command = app.add_subcommand(
      "optimize",
      "Minimise a design problem's cost (the paper's artificial variable b_{k+1}) subject to its constraints with "
      "one optimizer and one gradient method; prints an iteration table (cost, max violation, step, simulations and "
      "gradients so far) and a summary with the final design and its responses");
  addSceneArgument(*command, options->problem, true);
  command->add_option("--optimizer", options->optimizer, "The optimizer")
      ->check(CLI::IsMember(optimizerNames()))
      ->capture_default_str();
  std::vector<std::string> gradients = gradientMethodNames();
  gradients.push_back("fd");
  command->add_option("--gradient", options->gradient, "The gradient method (fd = fd_central)")
      ->check(CLI::IsMember(gradients))
      ->capture_default_str();
  command->add_option("--formulation", options->formulation,
                      "How each max-over-time constraint becomes one number: positive_part (the paper's ∫⟨φ⟩dt), "
                      "squared_positive_part (∫⟨φ⟩²dt), ks (Kreisselmeier-Steinhauser over the time mean) or "
                      "grid_max (the maximum over the time grid)")
      ->check(CLI::IsMember({"positive_part", "squared_positive_part", "ks", "grid_max"}))
      ->capture_default_str();
  command->add_option("--tolerance", options->tolerance,
                      "ε ≥ 0: each transcribed constraint is measure ≤ ε (the paper's form has a zero gradient where "
                      "satisfied; ε > 0 gives it an interior)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--max-iter", options->max_iterations,
                      "Iteration budget (NLopt: objective evaluations; Ipopt and SDCC: their own iterations)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--json", options->json,
                      "Write the result as JSON: problem, optimizer, gradient, formulation, status, message, design "
                      "(SI), responses, cost, max_violation, iterations, simulations, gradient_evaluations, "
                      "wall_time_s, history[{iteration, cost, max_violation, step, simulations, "
                      "gradient_evaluations}]");
  command->callback([options] { optimize(*options); });
}

}  // namespace mbsopt
