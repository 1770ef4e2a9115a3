#include "mbsopt/dynamics/integration.hpp"

#include <cmath>
#include <stdexcept>

namespace mbsopt {

const std::vector<IntegratorInfo>& integrators() {
  static const std::vector<IntegratorInfo> registry{
      {"newmark",
       "the paper's implicit Newmark scheme (trapezoidal rule, beta = 1/4, gamma = 1/2) at a fixed step, order 2; "
       "driven by accuracy, its step comes from the difference of runs at h and h/2",
       2},
      {"extrapolation",
       "global extrapolation of Newmark runs at H, H/2, H/3, ... (Aitken-Neville on the error's expansion in "
       "powers of h), order up to 10 when driven by accuracy (6 runs), 14 with --runs 8; driven by accuracy, it "
       "chooses H and the number of runs",
       6},
  };
  return registry;
}

std::string integratorNameList() {
  std::string names;
  for (const IntegratorInfo& info : integrators()) names += (names.empty() ? "" : ", ") + info.name;
  return names;
}

const IntegratorInfo& integratorInfo(const std::string& name) {
  for (const IntegratorInfo& info : integrators())
    if (info.name == name) return info;
  throw std::invalid_argument("unknown integrator '" + name + "' (known: " + integratorNameList() + ")");
}

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
  Trajectory& t = run.trajectory;
  const Eigen::Index points = (t.time.size() - 1) / stride + 1;
  const auto rows = Eigen::seqN(0, points, stride);
  t.time = Eigen::VectorXd(t.time(rows));
  for (Eigen::MatrixXd* columns : {&t.q, &t.v, &t.a, &t.lambda, &t.v_unprojected, &t.a_unprojected, &run.q_error,
                                   &run.v_error})
    if (columns->cols() > 0) *columns = Eigen::MatrixXd((*columns)(Eigen::all, rows));
  for (Eigen::MatrixXd* by_row : {&t.sensors, &run.sensor_error})
    if (by_row->rows() > 0) *by_row = Eigen::MatrixXd((*by_row)(rows, Eigen::all));
  if (t.closure_error.size() > 0) t.closure_error = Eigen::VectorXd(t.closure_error(rows));
  if (t.newton_iterations.size() > 0) t.newton_iterations = Eigen::VectorXi(t.newton_iterations(rows));
  t.step_matrices.resize(0, 0);
}

}  // namespace

Integration integrate(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& v0, const IntegrationRequest& request,
                      const std::function<void(double)>& progress) {
  const IntegratorInfo& info = integratorInfo(request.integrator);
  if (!(request.output_step >= 0.0 && std::isfinite(request.output_step)))
    throw std::invalid_argument("the output step must be positive and finite");
  if (request.output_step > settings.end_time)
    throw std::invalid_argument("the output step " + std::to_string(request.output_step) + " s is longer than the run (" +
                                std::to_string(settings.end_time) + " s)");
  Integration out;
  if (request.accuracy) {
    AccuracyGoal goal;
    goal.tolerance = *request.accuracy;
    goal.output_step = request.output_step;
    goal.max_runs = info.max_runs;
    AccurateRun accurate = simulateToAccuracy(model, settings, q0, v0, goal, progress);
    out.run = std::move(accurate.run);
    if (request.output_step > 0.0) keepEvery(out.run, stepsPerOutput(request.output_step, accurate.macro_step));
    out.estimated = true;
    out.control = std::move(accurate);
    out.control->run = {};
    return out;
  }
  if (info.name == "extrapolation") {
    NewmarkSettings macro = settings;
    if (request.output_step > 0.0) macro.step = request.output_step / std::ceil(request.output_step / settings.step - 1e-9);
    out.run = extrapolatedNewmark(model, macro, request.runs, q0, v0, progress);
    if (request.output_step > 0.0) keepEvery(out.run, stepsPerOutput(request.output_step, macro.step));
    out.estimated = true;
    return out;
  }
  const long stride = request.output_step > 0.0 ? stepsPerOutput(request.output_step, settings.step) : 1;
  Trajectory trajectory = NewmarkIntegrator(model, settings).simulate(q0, v0, progress);
  if (request.estimate_error) {
    out.run = estimateGlobalError(model, settings, std::move(trajectory), q0, v0, progress);
    out.estimated = true;
  } else {
    out.run.trajectory = std::move(trajectory);
    out.run.steps = {settings.step};
  }
  keepEvery(out.run, stride);
  return out;
}

}  // namespace mbsopt
