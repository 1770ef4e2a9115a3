#include "app/simulate_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/csv_output.hpp"
#include "app/scene_argument.hpp"
#include "mbsopt/problems/scene_text.hpp"

namespace mbsopt {

namespace {

struct SimulateOptions {
  SceneArgument scene;
  bool fast_newton = false;
  std::string step, end_time;  ///< as typed: they become overrides of settings.step, settings.end_time
  std::string out;
  long every = 1;  ///< write every N-th time point (and the last) to the CSV
};

/// Refuses, before a run, an output path that cannot or must not be replaced by the CSV.
void checkOutputPath(const SceneSource& source, const std::string& out) {
  namespace fs = std::filesystem;
  const fs::path path(out);
  const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code error;
  if (!fs::is_directory(directory, error))
    throw SceneError(source.path, 0, 0, "--out " + out + ": the directory " + directory.string() + " does not exist");
  const fs::file_status status = fs::symlink_status(path, error);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw SceneError(source.path, 0, 0, "--out " + out + ": exists and is not a regular file (a directory, a link "
                                        "or a device); give a file name");
  if (fs::exists(status) && fs::exists(source.path) && fs::equivalent(path, source.path, error))
    throw SceneError(source.path, 0, 0, "--out " + out + ": is the scene file itself");
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
  if (!options.out.empty()) checkOutputPath(source, options.out);
  LoadedScene loaded = loadScene(source, overrides);
  for (const std::string& warning : loaded.warnings) std::cerr << warning << '\n';
  Scene& scene = loaded.scene;
  scene.settings.accept_by_contraction_rate = options.fast_newton;

  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  const auto progress = [&](double t) {  // a line per second once a run takes longer than one
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report < std::chrono::seconds(1)) return;
    last_report = now;
    std::fprintf(stderr, "  t = %.4g s of %.4g s (%.0f%%), %.1f s elapsed\n", t, scene.settings.end_time,
                 100.0 * t / scene.settings.end_time, std::chrono::duration<double>(now - start).count());
  };
  Trajectory trajectory;
  try {
    trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0, progress);
  } catch (const SimulationError& e) {
    failAt(source, loaded, e.element, e.what());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

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
  for (std::size_t s = 0; s < scene.model.sensors().size(); ++s) {
    Eigen::Index at = 0;
    const double peak = sensors.col(static_cast<Eigen::Index>(s)).cwiseAbs().maxCoeff(&at);
    std::printf("  max |%s| = %.6g at t = %.4g s\n", scene.model.sensors()[s].name.c_str(), peak, trajectory.time[at]);
  }
  const IntegratorStatistics& stats = trajectory.statistics;
  std::printf("simulated %s: %ld steps of %g s, %ld Newton iterations, max closure error %.3g, max relative Newton "
              "residual %.3g, wall time %.3g s%s\n",
              source.path.c_str(), stats.steps, scene.settings.step, stats.newton_iterations, stats.max_closure_error,
              stats.max_relative_residual, wall, options.out.empty() ? "" : (", wrote " + options.out).c_str());
}

}  // namespace

void registerSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate a scene with the Newmark integrator: prints the peak of every sensor and a summary line "
      "(steps, Newton iterations, max closure error, wall time) on stdout, warnings and a progress line per "
      "second on stderr; exit status 1 with one line 'file:line:column: error: what' on a bad scene");
  addSceneArgument(*command, options->scene, true);
  command->add_option("--dt", options->step,
                      "Time step h [s]; the same as --set settings.step=H (default: the scene's settings.step)");
  command->add_option("--t-end", options->end_time,
                      "End time T [s]; the same as --set settings.end_time=T. The run takes ceil(T/h) steps, so it "
                      "ends at T or just after (default: the scene's settings.end_time)");
  command->add_flag("--fast-newton", options->fast_newton,
                    "Accept a first Newton iterate when the contraction rate measured on recent steps says it is "
                    "converged (about 30% faster; results then differ at 1e-8 relative, too noisy for finite-"
                    "difference gradients)");
  CLI::Option* out =
      command
          ->add_option("--out", options->out,
                       "CSV file: one row per time point (see --every) with t [s], every coordinate, then every "
                       "sensor, by name (SI units: m, rad, m/s², ...); written to a temporary name and renamed when "
                       "complete, so it never exists half written")
          ->check([](const std::string& path) { return path.empty() ? "the file name is empty" : ""; });
  command
      ->add_option("--every", options->every,
                   "Write only every N-th time point to the CSV, and always the first and the last (t = 0, N·h, "
                   "2N·h, ..., T); the peaks printed still cover every step (default 1: every step)")
      ->check(CLI::PositiveNumber)
      ->needs(out);
  command->callback([options] { run(*options); });
}

}  // namespace mbsopt
