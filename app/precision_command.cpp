#include "app/precision_command.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/scene_text.hpp"
#include "mbsopt/design/gradient_precision.hpp"
#include "mbsopt/design/precision_report.hpp"
#include "mbsopt/design/precision_study.hpp"
#include "app/design_point.hpp"
#include "app/option_checks.hpp"
#include "app/output_paths.hpp"
#include "app/scene_argument.hpp"

namespace mbsopt {

namespace {

struct PrecisionOptions {
  SceneArgument scene;
  bool gradients = false;
  std::vector<double> steps;
  std::optional<double> reference_step;
  std::vector<std::string> variants;  ///< integrator variants, or gradient methods with --gradients
  std::string reference;              ///< a CSV file
  std::vector<std::string> quantities;
  double alpha = 0.05;
  int runs = 4;  ///< the extrapolation variant's runs per macro step
  double fd_step = 1e-6;
  DesignPointRequest point;  ///< --design, --artificial, --outside-bounds (with --gradients)
  std::optional<int> repeat;
  std::optional<double> target_error;
  std::string out;
  std::string command_line;
};

constexpr int kIntegratorRepeat = 3, kGradientRepeat = 1;
const std::vector<double> kGradientSteps{2e-3, 1e-3, 5e-4, 2.5e-4};

/// The command as typed, from what CLI11 parsed (values quoted for the shell where needed).
std::string commandLine(const CLI::App& command) {
  const auto shell = [](const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || std::string("._,=+-/:").find(c) != std::string::npos;
    });
    return plain ? word : "'" + word + "'";
  };
  std::string line = "mbsopt " + command.get_name();
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_lnames().empty() ? "" : "--" + option->get_lnames()[0];
    if (option->get_positional()) {
      for (const std::string& value : option->results()) line += " " + shell(value);
    } else if (option->get_type_size() == 0) {
      line += " " + name;
    } else if (option->get_delimiter() != '\0') {
      std::string values;
      for (const std::string& value : option->results()) values += (values.empty() ? "" : ",") + value;
      line += " " + name + " " + shell(values);
    } else {
      for (const std::string& value : option->results()) line += " " + name + " " + shell(value);
    }
  }
  return line;
}

/// Descending, without repeats: the table and the curves then run from the cheapest run to the dearest.
std::vector<double> ladder(std::vector<double> steps) {
  std::sort(steps.begin(), steps.end(), std::greater<>());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::vector<std::string> quantityNames(const std::vector<Quantity>& quantities) {
  std::vector<std::string> names;
  for (const Quantity& q : quantities) names.push_back(q.name);
  return names;
}

/// The table, the target, and with --out the JSON (`study` plus the runs) and the plot.
void report(const PrecisionOptions& options, nlohmann::json study, const std::vector<PrecisionRun>& runs,
            const std::string& error_heading, const std::string& error_label, const std::string& title) {
  printPrecisionTable(runs, error_heading);
  if (options.target_error) printTarget(runs, *options.target_error);
  if (options.out.empty()) return;
  study["target_error"] = options.target_error ? nlohmann::json(*options.target_error) : nlohmann::json(nullptr);
  const PrecisionRun* best = options.target_error ? cheapestReaching(runs, *options.target_error) : nullptr;
  study["cheapest"] = best ? precisionRunJson(*best) : nlohmann::json(nullptr);
  study["runs"] = nlohmann::json::array();
  for (const PrecisionRun& run : runs) study["runs"].push_back(precisionRunJson(run));
  const std::filesystem::path directory(options.out);
  writeAtomically((directory / "precision.json").string(),
                  [&](std::ostream& out) { out << study.dump(2) << '\n'; });
  plotWorkPrecision((directory / "work_precision").string(), title, runs, error_label);
  std::printf("wrote %s and %s\n", (directory / "precision.json").c_str(), (directory / "work_precision.png").c_str());
}

/// Every (variant, step) of the sweep, variant by variant, with progress on stderr.
template <class Measure>
std::vector<PrecisionRun> sweep(const std::vector<std::string>& variants, const std::vector<double>& steps,
                                StudyProgress& progress, Measure&& measure) {
  std::vector<PrecisionRun> runs;
  for (const std::string& variant : variants)
    for (const double step : steps) {
      runs.push_back(measure(variant, step));
      const PrecisionRun& run = runs.back();
      progress.ran(variant + " at h = " + formatNumber(step) + " s: " +
                   (run.failed ? "failed" : "error " + shortNumber(run.error)));
    }
  return runs;
}

void integratorStudy(const PrecisionOptions& options, const SceneSource& source,
                     const std::vector<ParameterOverride>& overrides) {
  const LoadedScene loaded = loadScene(source, overrides);
  for (const std::string& warning : loaded.warnings) std::cerr << warning << '\n';
  const Scene& scene = loaded.scene;
  const double h = scene.settings.step, end_time = scene.settings.end_time;
  // Each step as the runs take it: the largest at most it that ends at the end time (uniformStep).
  std::vector<double> steps = ladder(options.steps.empty() ? std::vector{8 * h, 4 * h, 2 * h, h, h / 2} : options.steps);
  for (double& step : steps) step = uniformStep(step, end_time);
  const std::vector<std::string> variants = options.variants.empty() ? integratorVariantNames() : options.variants;
  for (const std::string& variant : variants) variantSettings(scene.settings, variant, options.alpha);  // names known?
  const int repeat = options.repeat.value_or(kIntegratorRepeat);
  StudyProgress progress(variants.size() * steps.size());

  ReferenceSolution reference;
  nlohmann::json reference_json;
  if (!options.reference.empty()) {
    reference = readReferenceCsv(options.reference, scene.model, options.quantities);
    try {
      requireOnGrids(reference.times, steps, end_time);
    } catch (const std::invalid_argument& e) {
      throw SceneError(options.reference, 0, 0, e.what());
    }
    reference_json = {{"kind", "file"}, {"file", reference.file}};
  } else {
    const double step = uniformStep(options.reference_step.value_or(steps.back() / 16), end_time);
    // Beside the extrapolation, a plain run at h/16 is no reference (the four-bar's at 1e-4 s is 6e-7
    // off, the extrapolation's error at 1e-3 s is 1e-8): it is then an extrapolation of 3 runs itself.
    const bool extrapolated = std::any_of(variants.begin(), variants.end(), runsExtrapolation) &&
                              extrapolationDefect(scene.settings).empty();
    const int reference_runs = extrapolated ? 3 : 1;
    std::vector<double> grids = steps;
    grids.push_back(step);
    const Eigen::VectorXd times = commonGridTimes(grids, end_time);
    try {
      reference = referenceRun(scene, step, reference_runs, times, options.quantities, [&](double t) {
        progress.say("reference run at h = " + formatNumber(step) + " s: t = " + formatNumber(t) + " s of " +
                     formatNumber(end_time) + " s");
      });
    } catch (const SimulationError& e) {
      throw std::runtime_error("the reference run at h = " + formatNumber(step) + " s failed: " + e.what());
    }
    reference_json = {{"kind", "run"},
                      {"variant", extrapolated ? "extrapolation" : "newmark"},
                      {"step", step},
                      {"runs", reference_runs},
                      {"wall_time_s", reference.seconds}};
  }
  std::printf("precision %s: %zu variants x %zu steps, median of %d runs each; reference: %s; error: max |difference| "
              "over %zu times (%.4g s to %.4g s) of %s\n",
              source.path.c_str(), variants.size(), steps.size(), repeat,
              reference.file.empty()
                  ? ((reference_json.value("runs", 1) > 1 ? "an extrapolation of " + std::to_string(reference_json.value("runs", 1)) + " runs at H = "
                                                          : std::string("a run at h = ")) +
                     formatNumber(reference.step) + " s")
                        .c_str()
                  : reference.file.c_str(),
              static_cast<std::size_t>(reference.times.size()), reference.times[0],
              reference.times[reference.times.size() - 1], listed(quantityNames(reference.quantities)).c_str());

  const std::vector<PrecisionRun> runs = sweep(variants, steps, progress, [&](const std::string& variant, double step) {
    return measureIntegratorRun(scene, variant, step, options.alpha, options.runs, reference, repeat);
  });
  nlohmann::json study = {{"command", options.command_line},
                          {"scene", source.path},
                          {"study", "integrator"},
                          {"error_measure", "largest absolute difference from the reference [SI units]"},
                          {"steps", steps},
                          {"variants", variants},
                          {"damping_alpha", options.alpha},
                          {"extrapolation_runs", options.runs},
                          {"repeat", repeat},
                          {"reference", reference_json},
                          {"quantities", quantityNames(reference.quantities)},
                          {"compared_times",
                           {{"count", reference.times.size()},
                            {"first", reference.times[0]},
                            {"last", reference.times[reference.times.size() - 1]}}}};
  report(options, study, runs, "max |error|", "largest absolute error [SI]",
         "work-precision of the integrator, " + source.path);
}

void gradientStudy(const PrecisionOptions& options, const SceneSource& source,
                   const std::vector<ParameterOverride>& overrides) {
  const DesignProblem problem = loadDesignProblem(source, overrides);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = checkedDesignPoint(source, overrides, problem, options.point);
  const std::vector<double> steps = ladder(options.steps.empty() ? kGradientSteps : options.steps);
  const std::vector<std::string> methods = options.variants.empty() ? gradientMethodNames() : options.variants;
  for (const std::string& method : methods) gradientMethod(method);  // an unknown name throws
  const int repeat = options.repeat.value_or(kGradientRepeat);
  StudyProgress progress(methods.size() * steps.size());

  const double step = options.reference_step.value_or(steps.back() / 4);
  std::fprintf(stderr, "  reference gradient: the direct method at h = %s s\n", formatNumber(step).c_str());
  GradientReference reference;
  try {
    reference = referenceGradient(problem, functionals, x, step);
  } catch (const SimulationError& e) {
    throw std::runtime_error("the reference gradient at h = " + formatNumber(step) + " s failed: " + e.what());
  }
  if (!dependsOnDesign(reference))
    std::fprintf(stderr, "mbsopt: warning: at this design point no functional's gradient depends on the design "
                         "variables (every constraint inactive), so the errors compare zeros; choose a point where "
                         "constraints are active with --design or --artificial (e.g. --artificial 2 on the tramway)\n");
  std::printf("precision %s --gradients: %zu methods x %zu steps, median of %d runs each; reference: %s at h = %s s "
              "(%.3g s); error: max relative difference of the gradient of each of %s\n",
              source.path.c_str(), methods.size(), steps.size(), repeat, reference.method.c_str(),
              formatNumber(step).c_str(), reference.seconds, listed(reference.functionals).c_str());

  const std::vector<PrecisionRun> runs = sweep(methods, steps, progress, [&](const std::string& method, double h) {
    return measureGradientRun(problem, functionals, x, method, h, options.fd_step, reference, repeat);
  });
  nlohmann::json study = {
      {"command", options.command_line},
      {"scene", source.path},
      {"study", "gradients"},
      {"error_measure", "largest over the functionals of max|g - g_ref| / max|g_ref|, g the gradient in the scaled "
                        "design variables (b_{k+1}'s column, exact and shared by every method, left out)"},
      {"steps", steps},
      {"variants", methods},
      {"fd_step", options.fd_step},
      {"repeat", repeat},
      {"reference", {{"kind", "gradient"}, {"variant", reference.method}, {"step", step},
                     {"wall_time_s", reference.seconds}}},
      {"functionals", reference.functionals},
      {"design_point", std::vector<double>(x.begin(), x.end())}};
  report(options, study, runs, "max rel. error", "largest relative error of the gradients",
         "work-precision of the design gradients, " + source.path);
}

void run(const PrecisionOptions& options) {
  checkOutputDirectory("--out", options.out);
  const SceneSource source = resolveScene(options.scene.scene);
  const std::vector<ParameterOverride> overrides = parseOverrides(source, options.scene.sets);
  if (options.gradients) gradientStudy(options, source, overrides);
  else integratorStudy(options, source, overrides);
}

}  // namespace

void registerPrecisionCommand(CLI::App& app) {
  auto options = std::make_shared<PrecisionOptions>();
  CLI::App* command = app.add_subcommand(
      "precision",
      "Work-precision study: run the scene at a ladder of steps h with several variants of the integrator, "
      "time each run (integration only, median of --repeat) and measure its error against a reference: the "
      "largest absolute difference, in SI units, of the compared quantities at the compared times. With "
      "--gradients, the same for the design gradients of the scene's design problem. Prints a table (variant, "
      "h, error, time, steps, Newton iterations; failed runs with their message), progress on stderr when the "
      "study takes longer than a second; --out DIR writes precision.json and work_precision.png (error against "
      "wall time, log-log, one curve per variant)");
  addSceneArgument(*command, options->scene, true);
  command->add_option("--steps", options->steps,
                      "The steps h [s] to sweep, e.g. 2e-2,1e-2,5e-3 (default: 8h, 4h, 2h, h, h/2 with h the scene's "
                      "settings.step; with --gradients 2e-3,1e-3,5e-4,2.5e-4)")
      ->delimiter(',')
      ->check(positiveNumber());
  command->add_option("--variants", options->variants,
                      "Comma-separated variants (default: all): newmark (the scene's beta, gamma), damped (numerical "
                      "damping: gamma = 1/2 + alpha, beta = (gamma + 1/2)^2/4), fast-newton (accept a Newton iterate "
                      "by contraction rate), fast-steps (Newton to 1e-3 of the step's truncation error, SVDs from the "
                      "last step's: simulate --fast-steps), acceleration-closure (loops closed at the acceleration level), extrapolation "
                      "(runs at h, h/2, ..., h/K combined, K = --runs; h is its macro step; it reports its own "
                      "error estimate beside the error). With "
                      "--gradients: gradient methods (default all: " +
                          listed(gradientMethodNames()) + ")")
      ->delimiter(',');
  CLI::Option* alpha =
      command->add_option("--alpha", options->alpha, "The numerical damping alpha of the damped variant")
          ->check(numberBetween(0.0, 0.5));
  CLI::Option* runs = command->add_option("--runs", options->runs, "Runs per macro step of the extrapolation variant")
                          ->check(integerBetween(2, kMaxExtrapolationRuns))
                          ->capture_default_str();
  CLI::Option* reference =
      command->add_option("--reference", options->reference,
                          "Reference CSV: a header 't,<name>,...' (coordinates or sensors of the scene, e.g. as "
                          "written by 'mbsopt simulate --out', with --every), one row per output time; the errors "
                          "are measured at its times, which must lie on the grid of every swept step (default: a "
                          "run of the scene at --reference-step, compared at the grid points common to all steps)");
  command->add_option("--reference-step", options->reference_step,
                      "Step of the reference run [s] (default: the smallest swept step / 16; with --gradients, the "
                      "step of the reference gradient, by the direct method, default the smallest step / 4)")
      ->check(positiveNumber())
      ->excludes(reference);
  CLI::Option* quantities =
      command->add_option("--quantities", options->quantities,
                          "Comma-separated coordinates or sensors to compare (default: every sensor of the reference "
                          "file, or every coordinate when the reference is a run)")
          ->delimiter(',');
  command->add_option("--repeat", options->repeat,
                      "Runs per (variant, step); the time is their median (default 3; 1 with --gradients)")
      ->check(integerBetween(1, 1000));
  command->add_option("--target-error", options->target_error,
                      "Print the variant and step that reach this error in the least time (or that none does)")
      ->check(positiveNumber());
  command->add_option("--out", options->out,
                      "Directory (created if missing) for precision.json (command, scene, study, reference, "
                      "quantities or functionals, steps, variants, repeat, target_error, cheapest, runs[{variant, "
                      "step, status, message, error, errors{name: error}, wall_time_s, steps, newton_iterations}]) "
                      "and work_precision.png (with its .dat and .gp)");
  CLI::Option* gradients = command->add_flag(
      "--gradients", options->gradients,
      "Study the design gradients instead (the scene needs a design: section): for each step and gradient method, "
      "the largest relative error of the gradient of every functional (the cost b_{k+1} and each transcribed "
      "constraint, as 'mbsopt gradcheck' prints them) in the design variables against the direct method at "
      "--reference-step, at the scene's design point or the one of --design and --artificial");
  command->add_option("--fd-step", options->fd_step,
                      "With --gradients: the relative step of the finite-difference methods")
      ->check(positiveNumber())
      ->needs(gradients);
  for (CLI::Option* point : addDesignPointOptions(*command, options->point, "With --gradients: ")) point->needs(gradients);
  gradients->excludes(reference)->excludes(quantities)->excludes(alpha)->excludes(runs);
  command->callback([options, command] {
    options->command_line = commandLine(*command);
    locatingRunFailures(options->scene, [&] { run(*options); });
  });
}

}  // namespace mbsopt
