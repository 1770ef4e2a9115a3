#include "mbsopt/integrators/integration.hpp"

#include <cmath>
#include <stdexcept>

#include "mbsopt/integrators/adaptive_newmark.hpp"
#include "mbsopt/integrators/integrator_choice.hpp"

namespace mbsopt {

const std::vector<IntegratorInfo>& integrators() {
  static const std::vector<IntegratorInfo> registry{
      {"newmark",
       "the paper's implicit Newmark scheme (trapezoidal rule, beta = 1/4, gamma = 1/2) at a fixed step, order 2; "
       "driven by accuracy, its step comes from the difference of runs at h and h/2",
       2, false, false},
      {"extrapolation",
       "global extrapolation of Newmark runs at H, H/2, H/3, ... (Aitken-Neville on the error's expansion in "
       "powers of h), order up to 10 when driven by accuracy (6 runs), 14 with --runs 8; driven by accuracy, it "
       "chooses H and the number of runs",
       6, true, false},
      {"adaptive",
       "the same Newmark scheme at variable steps, each step's local error (1/12 h^2 times the change of the "
       "accelerations, Zienkiewicz-Xie) held to the tolerance; order 2; driven by accuracy, the local tolerance is "
       "tightened until the global estimate (the same steps halved) meets it",
       2, false, true},
  };
  return registry;
}

std::vector<std::string> integratorNames() {
  std::vector<std::string> names;
  for (const IntegratorInfo& info : integrators()) names.push_back(info.name);
  return names;
}

std::string integratorNameList() {
  std::string list;
  for (const std::string& name : integratorNames()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

const IntegratorInfo& integratorInfo(const std::string& name) {
  for (const IntegratorInfo& info : integrators())
    if (info.name == name) return info;
  throw std::invalid_argument("unknown integrator '" + name + "' (known: " + integratorNameList() + ")");
}

bool IntegratorChoice::extrapolated() const { return integratorInfo(name).extrapolated; }
bool IntegratorChoice::adaptive() const { return integratorInfo(name).variable_steps; }

namespace {

/// The number of steps of `step` in `output_step`; std::invalid_argument unless it is whole.
long stepsPerOutput(double output_step, double step) {
  const double ratio = output_step / step;
  const long whole = std::lround(ratio);
  if (whole < 1 || std::abs(ratio - static_cast<double>(whole)) > 1e-9 * ratio)
    throw std::invalid_argument("the output step " + std::to_string(output_step) + " s is not a whole number of steps of " +
                                std::to_string(step) + " s");
  return whole;
}

/// Keeps every `stride`-th time point (and the estimates there).
void keepEvery(EstimatedRun& run, long stride) {
  if (stride == 1) return;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < run.trajectory.time.size(); k += stride) kept.push_back(k);
  keepPoints(run, kept);
}

/// An adaptive run at the request's local tolerance (its `accuracy` is the goal of a run driven by
/// accuracy, so here the default ErrorTolerance), with its estimate when asked for.
Integration adaptiveIntegration(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                                const Eigen::VectorXd& v0, const IntegrationRequest& request,
                                const std::function<void(double)>& progress) {
  LocalErrorControl control;
  control.tolerance = ErrorTolerance{request.integrator.local_tolerance, 0.0};
  control.stop_times = outputTimes(request.output_step, settings.end_time);
  AdaptiveRun adaptive = adaptiveNewmarkRun(model, settings, q0, v0, control, progress);
  NewmarkSettings grid = settings;  // the steps it took
  grid.time_grid = timeGrid(adaptive.trajectory.time);
  Integration out;
  if (request.estimate_error) {
    out.run = estimateGlobalError(model, grid, std::move(adaptive.trajectory), q0, v0, progress);
    out.estimated = true;
  } else {
    out.run.trajectory = std::move(adaptive.trajectory);
  }
  out.run.steps = {largestStep(grid)};
  if (request.output_step > 0.0) keepPoints(out.run, adaptive.stops);
  return out;
}

}  // namespace

IntegrationRequest sceneIntegration(const Scene& scene, const std::optional<std::string>& integrator,
                                    const std::optional<ErrorTolerance>& accuracy) {
  IntegrationRequest request;
  request.integrator = scene.integrator;
  request.integrator.name = integrator ? *integrator : accuracy ? "extrapolation" : scene.integrator.name;
  integratorInfo(request.integrator.name);  // an unknown name throws
  request.accuracy = accuracy;
  return request;
}

Integration integrate(const Model& model, const NewmarkSettings& scene_settings, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& v0, const IntegrationRequest& scene_request,
                      const std::function<void(double)>& progress) {
  const IntegratorInfo& info = integratorInfo(scene_request.integrator.name);
  if (!(scene_request.output_step >= 0.0 && std::isfinite(scene_request.output_step)))
    throw std::invalid_argument("the output step must be positive and finite");
  if (scene_request.output_step > scene_settings.end_time * (1.0 + 1e-12))
    throw std::invalid_argument("the output step " + std::to_string(scene_request.output_step) +
                                " s is longer than the run (" + std::to_string(scene_settings.end_time) + " s)");
  // The run ends at T: the output interval divides [0, T] into whole intervals, the step divides the
  // output interval (each at most as long as asked).
  IntegrationRequest request = scene_request;
  NewmarkSettings settings = scene_settings;
  if (request.output_step > 0.0) {
    request.output_step = uniformStep(request.output_step, settings.end_time);
    settings.step = uniformStep(settings.step, request.output_step);
  }
  Integration out;
  if (request.accuracy) {
    AccuracyGoal goal;
    goal.tolerance = *request.accuracy;
    goal.output_step = request.output_step;
    goal.max_runs = info.max_runs;
    const bool adaptive = info.variable_steps;
    AccurateRun accurate = adaptive ? adaptiveToAccuracy(model, settings, q0, v0, goal, progress)
                                    : simulateToAccuracy(model, settings, q0, v0, goal, progress);
    out.run = std::move(accurate.run);
    if (request.output_step > 0.0 && !adaptive)  // an adaptive run's steps end at the output times
      keepEvery(out.run, stepsPerOutput(request.output_step, accurate.macro_step));
    out.estimated = true;
    out.control = std::move(accurate);
    out.control->run = {};
    return out;
  }
  const long stride = request.output_step > 0.0 ? stepsPerOutput(request.output_step, settings.step) : 1;
  if (info.extrapolated) {
    out.run = extrapolatedNewmark(model, settings, request.integrator.extrapolation_runs, q0, v0, progress);
    keepEvery(out.run, stride);
    out.estimated = true;
    return out;
  }
  if (info.variable_steps) return adaptiveIntegration(model, settings, q0, v0, request, progress);
  Trajectory trajectory = NewmarkIntegrator(model, settings).simulate(q0, v0, progress);
  if (request.estimate_error) {
    out.run = estimateGlobalError(model, settings, std::move(trajectory), q0, v0, progress);
    out.estimated = true;
  } else {
    out.run.trajectory = std::move(trajectory);
    out.run.steps = {uniformStep(settings)};
  }
  keepEvery(out.run, stride);
  return out;
}

}  // namespace mbsopt
