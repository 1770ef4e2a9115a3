#include "app/simulate_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/scene_text.hpp"
#include "mbsopt/io/trajectory_csv.hpp"
#include "app/option_checks.hpp"
#include "app/output_paths.hpp"
#include "app/registry_choices.hpp"
#include "app/scene_argument.hpp"
#include "app/simulation_summary.hpp"

namespace mbsopt {

namespace {

/// A fixed-step Newmark run estimates its global error by default up to this many steps (the estimate
/// takes a second run at h/2, twice the work of the first).
constexpr long kEstimateByDefaultUpTo = 200000;

struct SimulateOptions {
  SceneArgument scene;
  bool fast_newton = false;
  bool fast_steps = false;
  std::string step, end_time;  ///< as typed: they become overrides of settings.step, settings.end_time
  std::string out, json;
  long every = 1;  ///< write every N-th time point (and the last) to the CSV
  /// Empty: the scene's settings.integrator at a fixed step, extrapolation with --accuracy.
  std::string integrator;
  double accuracy = 0.0;           ///< the absolute part; 0: a fixed step
  double relative_accuracy = 0.0;  ///< the relative part
  double local_tolerance = 0.0;    ///< adaptive without --accuracy; 0: ErrorTolerance's default
  double output_step = 0.0;
  int runs = 0;  ///< 0: the scene's settings.extrapolation_runs
  std::string error_estimate = "auto";
  double warn_error = 1e-3;
};

IntegrationRequest requestOf(const SimulateOptions& options, const Scene& scene) {
  const NewmarkSettings& settings = scene.settings;
  IntegrationRequest request = sceneIntegration(
      scene, options.integrator.empty() ? std::nullopt : std::optional<std::string>(options.integrator),
      options.accuracy > 0.0 ? std::optional<ErrorTolerance>(ErrorTolerance{options.accuracy, options.relative_accuracy})
                             : std::nullopt);
  if (options.local_tolerance > 0.0) request.integrator.local_tolerance = options.local_tolerance;
  if (options.runs > 0) request.integrator.extrapolation_runs = options.runs;
  request.output_step = options.output_step;
  const double steps = static_cast<double>(stepsToCover(settings.end_time, settings.step));
  // auto: not for a scheme whose error is not even in h (damped β, γ; --fast-newton), where "on" is refused;
  // an adaptive run's steps are not known before it, so auto estimates it.
  request.estimate_error =
      options.error_estimate == "on" ||
      (options.error_estimate == "auto" &&
       (request.integrator.adaptive() || steps <= static_cast<double>(kEstimateByDefaultUpTo)) &&
       halvingDefect(settings, "the global error estimate").empty());
  return request;
}

/// An error in the run names an element; the file says where that element is declared.
[[noreturn]] void failAt(const SceneSource& source, const LoadedScene& loaded, const std::string& element,
                         const std::string& what) {
  const auto where = loaded.locations.find(element);
  if (where == loaded.locations.end()) throw SceneError(source.path, 0, 0, what);
  throw SceneError(source.path, where->second.line, where->second.column, what);
}

void run(const SimulateOptions& options) {
  const SceneSource source = resolveScene(options.scene.scene);
  std::vector<ParameterOverride> overrides = parseOverrides(source, options.scene.sets);
  for (const auto& [text, name] : {std::pair{options.step, "settings.step"}, {options.end_time, "settings.end_time"}})
    if (!text.empty()) overrides.push_back(parseOverride(source, name, text));
  checkOutputFile("--out", options.out, source.path);
  checkOutputFile("--json", options.json, source.path);
  LoadedScene loaded = loadScene(source, overrides);
  for (const std::string& warning : loaded.warnings) std::cerr << warning << '\n';
  Scene& scene = loaded.scene;
  scene.settings.accept_by_contraction_rate = options.fast_newton;
  if (options.fast_steps) scene.settings = withFastSteps(scene.settings);

  const IntegrationRequest request = requestOf(options, scene);
  if (!request.accuracy && request.integrator.extrapolated())
    if (const std::string defect = extrapolationDefect(scene.settings); !defect.empty())
      throw SceneError(source.path, 0, 0, defect);
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  double last_time = -1.0;
  int run_index = 0;
  const auto progress = [&](double t) {  // a line per second once a run takes longer than one
    if (t < last_time) ++run_index;  // the next of several runs
    last_time = t;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report < std::chrono::seconds(1)) return;
    last_report = now;
    std::fprintf(stderr, "  run %d: t = %.4g s of %.4g s (%.0f%%), %.1f s elapsed\n", run_index + 1, t,
                 scene.settings.end_time, 100.0 * t / scene.settings.end_time,
                 std::chrono::duration<double>(now - start).count());
  };
  Integration integration;
  try {
    integration = integrate(scene.model, scene.settings, scene.q0, scene.v0, request, progress);
  } catch (const SimulationError& e) {
    failAt(source, loaded, e.element, e.what());
  } catch (const AccuracyError& e) {
    throw SceneError(source.path, 0, 0, e.what());
  } catch (const std::invalid_argument& e) {
    throw SceneError(source.path, 0, 0, e.what());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Trajectory& trajectory = integration.run.trajectory;

  const Eigen::MatrixXd& sensors = trajectory.sensors;
  for (std::size_t s = 0; s < scene.model.sensors().size(); ++s) {
    const Eigen::Index column = static_cast<Eigen::Index>(s);
    const std::string& name = scene.model.sensors()[s].name;
    if (!sensors.col(column).allFinite()) {
      Eigen::Index k = 0;
      while (std::isfinite(sensors(k, column))) ++k;
      failAt(source, loaded, name,
             "sensor '" + name + "' is not finite at t = " + formatNumber(trajectory.time[k]) + " s");
    }
  }
  if (!options.out.empty()) writeTrajectoryCsv(options.out, scene.model, trajectory, sensors, options.every);
  SimulationSummary summary =
      summarize(scene.model, source.path, integration, request, scene.settings, wall, options.warn_error);
  // The JSON's warnings are every one the run printed: the loader's (on stderr above) first.
  summary.json["warnings"] = loaded.warnings;
  for (const std::string& warning : summary.warnings) summary.json["warnings"].push_back(warning);
  summary.json["left_out"] = loaded.left_out;  // of a model file, by `model: {ignore: …}`
  for (const std::string& line : summary.sensor_lines) std::printf("%s\n", line.c_str());
  for (const std::string& warning : summary.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  std::printf("%s%s\n", summary.line.c_str(), options.out.empty() ? "" : (", wrote " + options.out).c_str());
  if (!options.json.empty())
    writeAtomically(options.json, [&](std::ostream& out) { out << summary.json.dump(2) << '\n'; });
}

}  // namespace

void registerSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate a scene (the Newmark integrator at the scene's step by default): prints the peak of every "
      "sensor and a summary line (integrator, steps, Newton iterations, max closure error, the estimated global "
      "error, wall time) on stdout, warnings and a progress line per second on stderr; exit status 1 with one "
      "line 'file:line:column: error: what' on a bad scene or a run that fails");
  addSceneArgument(*command, options->scene, true);
  command->add_option("--dt", options->step,
                      "Time step h [s], at most the end time; the same as --set settings.step=H. The run takes "
                      "N = ceil(T/h) equal steps of T/N, so that it ends at T exactly (T/N = h where T/h is whole; "
                      "the summary prints the step taken) (default: the scene's settings.step)");
  command->add_option("--t-end", options->end_time,
                      "End time T [s]; the same as --set settings.end_time=T. Every run ends at T exactly (see --dt) "
                      "(default: the scene's settings.end_time)");
  command->add_flag("--fast-newton", options->fast_newton,
                    "Accept a first Newton iterate when the contraction rate measured on recent steps says it is "
                    "converged (about 30% faster; results then differ at 1e-8 relative, too noisy for finite-"
                    "difference gradients)");
  command->add_flag("--fast-steps", options->fast_steps,
                    "Solve each step only as precisely as it approximates the motion: Newton stops once its error is "
                    "below 0.1% of the step's truncation error (Zienkiewicz-Xie's estimate) instead of at the Newton "
                    "tolerance, and each step's SVD of the constraint Jacobian starts from the last one's. 2-3x fewer "
                    "Newton iterations at coarse steps, the global error within 1% of the default run's; not with "
                    "extrapolation, whose runs' differences must be the discretisation's");
  CLI::Option* out =
      command
          ->add_option("--out", options->out,
                       "CSV file: one row per time point (see --every) with t, every coordinate, then every sensor, "
                       "each column headed 'name [unit]' (SI: s, m, rad, m/s², N, ...; a relative angle in rad) and "
                       "written to 17 significant digits; written to a temporary name and renamed when complete, so "
                       "it never exists half written")
          ->check([](const std::string& path) { return path.empty() ? "the file name is empty" : ""; });
  command
      ->add_option("--integrator", options->integrator,
                   "The integrator (default: the scene's settings.integrator, newmark unless it says; extrapolation with "
                   "--accuracy): " + describedChoices(integrators()))
      ->check(CLI::IsMember(integratorNames()));
  CLI::Option* accuracy =
      command
          ->add_option("--accuracy", options->accuracy,
                       "Run to this accuracy instead of at a fixed step: the steps (and, for extrapolation, the "
                       "number of runs) are chosen until the estimated global error e of every coordinate q meets "
                       "|e| <= TOL + R |q| at every output time, in the coordinate's unit (rad or m; R: "
                       "--relative-accuracy, default 0: an angle that winds up over many turns would otherwise be "
                       "allowed a larger error with every turn); the estimate is printed. Where Newton runs at the "
                       "scene's tolerance (TOL <= 1e-7 by default), an extrapolation of 4 runs or more is rounded a "
                       "second time (its runs repeated at steps a few ulps longer) and the round-off floor this "
                       "measures is included in the estimate: about twice the work, and below the floor the run "
                       "says so instead of claiming an accuracy it cannot have")
          ->check(positiveNumber());
  command
      ->add_option("--relative-accuracy", options->relative_accuracy,
                   "The relative part R of --accuracy (IDA's rtol beside its atol)")
      ->check(nonNegativeNumber())
      ->needs(accuracy);
  command
      ->add_option("--local-tolerance", options->local_tolerance,
                   "The adaptive integrator without --accuracy: each step's local error in a coordinate (1/12 h^2 "
                   "times the change of its acceleration over the step) at most TOL, in its unit (default: the scene's "
                   "settings.local_tolerance, 1e-6 unless it says); the global error is what the estimate says")
      ->check(positiveNumber())
      ->excludes(accuracy);
  command
      ->add_option("--output-step", options->output_step,
                   "Results (CSV rows, peaks, the estimate) at equal intervals of at most DT [s], M = ceil(T/DT) of "
                   "them so that the last is at T, whatever steps the integrator takes (an adaptive run's steps end "
                   "there; a fixed step or macro step is shortened to a whole number per interval) (default: every "
                   "step, or every macro step of an extrapolation)")
      ->check(positiveNumber());
  command
      ->add_option("--runs", options->runs,
                   "Extrapolation at a fixed macro step (no --accuracy): Newmark runs at H, H/2, ..., H/K with H "
                   "the scene's step; the result has order K (2K - 2 without cut joints) (default: the scene's "
                   "settings.extrapolation_runs, 3 unless it says)")
      ->check(integerBetween(2, kMaxExtrapolationRuns))
      ->excludes(accuracy);
  command
      ->add_option("--error-estimate", options->error_estimate,
                   "For a fixed Newmark step or an adaptive run: estimate the global error from a second run at "
                   "its steps halved (twice the work of the first): on, off, or auto (on up to " +
                       std::to_string(kEstimateByDefaultUpTo) +
                       " fixed steps, and for an adaptive run). Extrapolation and --accuracy always estimate it")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  command
      ->add_option("--warn-error", options->warn_error,
                   "Warn on stderr when the estimated global error of a coordinate exceeds TOL + TOL |q|")
      ->check(positiveNumber())
      ->capture_default_str();
  command->add_option("--json", options->json,
                      "Write the run's summary as JSON: integrator, steps, the estimated global errors (largest "
                      "over the coordinates and rates, weighted, per sensor), each sensor's {name, unit (SI), max_abs, "
                      "at_time [s], estimated_error}, warnings (every one printed, the loader's first), left_out (what "
                      "`model: {ignore: …}` left out of a model file, a line per feature), wall time");
  command
      ->add_option("--every", options->every,
                   "Write only every N-th time point to the CSV, and always the first and the last (t = 0, N·h, "
                   "2N·h, ..., T); the peaks printed still cover every time point of the run (every step of a "
                   "fixed Newmark step; the output times of --output-step and of the extrapolation) (default 1)")
      ->check(positiveInteger())
      ->needs(out);
  command->callback([options] { run(*options); });
}

}  // namespace mbsopt
