#include "app/gradcheck_command.hpp"

#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/scene_text.hpp"
#include "mbsopt/design/gradient_difference.hpp"
#include "app/design_point.hpp"
#include "app/option_checks.hpp"
#include "app/output_paths.hpp"
#include "app/scene_argument.hpp"

namespace mbsopt {

namespace {

struct GradcheckOptions {
  SceneArgument problem;
  DesignPointRequest point;
  double fd_step = 1e-6;
  std::string json;
};

/// One method's gradient, or why it has none.
struct MethodResult {
  std::string name;
  std::optional<DesignGradient> gradient;
  std::string unavailable;
  double seconds = 0.0;
};

template <class Compute>
MethodResult run(const std::string& name, Compute&& compute) {
  MethodResult result{name, std::nullopt, "", 0.0};
  const auto start = std::chrono::steady_clock::now();
  try {
    result.gradient = compute();
  } catch (const std::invalid_argument& e) {
    result.unavailable = e.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<double> toVector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

void gradcheck(const GradcheckOptions& options) {
  const SceneSource source = resolveScene(options.problem.scene);
  checkOutputFile("--json", options.json, source.path);
  const std::vector<ParameterOverride> overrides = parseOverrides(source, options.problem.sets);
  const DesignProblem problem = loadDesignProblem(source, overrides);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = checkedDesignPoint(source, overrides, problem, options.point);
  const std::vector<std::string> outside = outsideBounds(problem, x);

  const auto start = std::chrono::steady_clock::now();
  const DesignResponse response = evaluateDesign(problem, functionals, x);
  const double simulation = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<MethodResult> methods;
  for (const std::string& name : gradientMethodNames())
    methods.push_back(run(name, [&] { return designGradient(name, problem, functionals, x, options.fd_step); }));
  const MethodResult& reference = methods[0].gradient ? methods[0] : methods.back();  // adjoint, else fd_central

  // A step that leaves the model invalid (a mass or an inertia out of range) is left out of the sweep.
  std::vector<std::pair<double, DesignGradient>> sweep;
  for (double step = 1e-2; step > 0.5e-9; step /= 10.0) {
    try {
      sweep.emplace_back(step, finiteDifferenceGradient(problem, functionals, x, step, true));
    } catch (const std::invalid_argument& e) {
      std::printf("  central differences with relative step %.0e left out: %s\n", step, e.what());
    }
  }

  // Text report.
  std::printf("gradcheck %s: %zu design variables + b_{k+1}, %zu constraints; one simulation %.3g s\n",
              source.path.c_str(), problem.design.variables.size(), functionals.size(), simulation);
  for (const std::string& value : outside) std::printf("OUTSIDE THE DESIGN'S BOUNDS (--outside-bounds): %s\n", value.c_str());
  // The gradients' columns: ∂/∂x_i, x_i = value_i / scale_i (the units the optimizers see).
  nlohmann::json json_variables = nlohmann::json::array();
  std::printf("columns, d/dx with x = value/scale:");
  for (const DesignVariable& v : problem.design.variables) {
    std::printf(" %s (scale %g),", v.parameter.c_str(), v.scale);
    json_variables.push_back({{"name", v.parameter}, {"scale", v.scale}});
  }
  std::printf(" b_{k+1} (scale %g)\n", problem.design.artificial.scale);
  json_variables.push_back({{"name", "b_{k+1}"}, {"scale", problem.design.artificial.scale}});
  // Differences are measured over the design variables' columns, as `mbsopt precision` measures them
  // (gradient_precision.cpp): the b_{k+1} column is exact in every method (1 for the cost, minus
  // the time the bound is exceeded for a constraint) and, often a row's largest entry, would
  // flatter the other columns' errors by normalising them.
  const Eigen::Index design = static_cast<Eigen::Index>(problem.design.variables.size());
  const auto difference = [&](const DesignGradient& g, Eigen::Index r) {
    return relativeDifference(functionalGradient(g, r).head(design),
                              functionalGradient(*reference.gradient, r).head(design));
  };
  for (const MethodResult& m : methods) {
    if (!m.gradient) {
      std::printf("  %-19s not available: %s\n", m.name.c_str(), m.unavailable.c_str());
      continue;
    }
    double worst = 0.0;
    for (Eigen::Index r = 0; r <= static_cast<Eigen::Index>(functionals.size()); ++r)
      worst = std::max(worst, difference(*m.gradient, r));
    std::printf("  %-19s %8.3g s  max relative difference from %s %.2e\n", m.name.c_str(), m.seconds,
                reference.name.c_str(), worst);
  }
  nlohmann::json json_functionals = nlohmann::json::array();
  for (Eigen::Index r = 0; r <= static_cast<Eigen::Index>(functionals.size()); ++r) {
    const std::string name = r == 0 ? "cost" : functionals[static_cast<std::size_t>(r - 1)].name;
    const double value = r == 0 ? response.cost : response.constraints[r - 1];
    std::printf("%s = %s\n", name.c_str(), formatNumber(value).c_str());
    nlohmann::json gradients = nlohmann::json::object();
    for (const MethodResult& m : methods) {
      if (!m.gradient) continue;
      const Eigen::VectorXd g = functionalGradient(*m.gradient, r);
      gradients[m.name] = toVector(g);
      std::printf("  %-19s", m.name.c_str());
      for (Eigen::Index i = 0; i < g.size(); ++i) std::printf(" %13.6e", g[i]);
      std::printf("\n");
    }
    std::printf("  central differences, relative step: relative difference from %s\n   ", reference.name.c_str());
    nlohmann::json json_sweep = nlohmann::json::array();
    for (const auto& [step, g] : sweep) {
      std::printf(" %.0e: %.1e", step, difference(g, r));
      json_sweep.push_back({{"relative_step", step}, {"gradient", toVector(functionalGradient(g, r))}});
    }
    std::printf("\n");
    json_functionals.push_back({{"name", name}, {"value", value}, {"gradients", gradients}, {"fd_sweep", json_sweep}});
  }
  if (!options.json.empty()) {
    nlohmann::json timings = {{"simulation", simulation}};
    for (const MethodResult& m : methods)
      if (m.gradient) timings[m.name] = m.seconds;
    const nlohmann::json document = {{"problem", source.path},
                                     {"variables", json_variables},
                                     {"design_point", toVector(x)},
                                     {"outside_bounds", outside},
                                     {"functionals", json_functionals},
                                     {"timings_s", timings}};
    writeAtomically(options.json, [&](std::ostream& out) { out << document.dump(2) << '\n'; });
  }
}

}  // namespace

void registerGradcheckCommand(CLI::App& app) {
  auto options = std::make_shared<GradcheckOptions>();
  CLI::App* command = app.add_subcommand(
      "gradcheck",
      "At a design point, print each functional (the cost b_{k+1} and every transcribed constraint) and its "
      "gradient with respect to the scaled design variables by every method (adjoint, continuous-adjoint, direct, "
      "forward and central differences), their differences from the adjoint (max |g - adjoint| / max |adjoint| "
      "over the design variables' columns; b_{k+1}'s is exact in every method), a sweep of central-difference "
      "steps from 1e-2 to 1e-9 (the V shape) and the time of each method");
  addSceneArgument(*command, options->problem, true);
  addDesignPointOptions(*command, options->point);
  command->add_option("--fd-step", options->fd_step, "Relative step of the forward and central differences")
      ->check(positiveNumber());
  command->add_option("--json", options->json,
                      "Write the results as JSON: variables[{name, scale}] (the gradients' columns, d/dx with x = "
                      "value/scale, b_{k+1} last), design_point (x), outside_bounds (the values outside the design's bounds, --outside-bounds), functionals[{name, value, gradients{method: [..]}, "
                      "fd_sweep[{relative_step, gradient}]}], timings_s{simulation, method: seconds}");
  command->callback([options] { locatingRunFailures(options->problem, [&] { gradcheck(*options); }); });
}

}  // namespace mbsopt
