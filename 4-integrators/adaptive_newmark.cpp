#include "mbsopt/integrators/adaptive_newmark.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/trajectory.hpp"

namespace mbsopt {

namespace {

// The step controller's factors: the next step is h·clamp(kSafety·err^{−1/3}, kSmallest, kLargest);
// a step Newton cannot solve is retried at kAfterFailure·h. (Keeping an accepted step unless it may
// grow by 1.5 at least, as IDA does so that Newton's start extrapolates at equal spacing, saved no
// time and cost accuracy: 9.7e-5 instead of 1.3e-5 on the four-bar at τ = 1e-8 for as many steps.)
constexpr double kSafety = 0.9, kSmallest = 0.2, kLargest = 2.0, kAfterFailure = 0.25;
// Below this fraction of the end time a step is not tried: the run fails there.
constexpr double kSmallestStep = 1e-12;

/// Appends the integrator's state to the columns kept so far: each quantity one flat array, column after
/// column, so that a step allocates nothing but the arrays' amortized growth.
struct GrowingTrajectory {
  std::vector<double> time, q, v, a, lambda, closure_error;
  std::vector<int> newton_iterations;

  void keep(const NewmarkIntegrator& integrator, int iterations) {
    time.push_back(integrator.time());
    for (auto [kept, column] : {std::pair{&q, &integrator.q()}, {&v, &integrator.v()}, {&a, &integrator.a()},
                                {&lambda, &integrator.lambda()}})
      kept->insert(kept->end(), column->data(), column->data() + column->size());
    closure_error.push_back(integrator.closureError());
    newton_iterations.push_back(iterations);
  }

  Trajectory finish(const Model& model, const IntegratorStatistics& statistics) const {
    const auto points = static_cast<Eigen::Index>(time.size());
    const auto columns = [&](const std::vector<double>& kept, Eigen::Index rows) {
      return Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(kept.data(), rows, points));
    };
    Trajectory out;
    out.time = Eigen::Map<const Eigen::VectorXd>(time.data(), points);
    out.q = columns(q, model.coordinateCount());
    out.v = columns(v, model.coordinateCount());
    out.a = columns(a, model.coordinateCount());
    out.lambda = columns(lambda, model.constraintCount());
    out.closure_error = Eigen::Map<const Eigen::VectorXd>(closure_error.data(), points);
    out.newton_iterations = Eigen::Map<const Eigen::VectorXi>(newton_iterations.data(), points);
    out.sensors = sensorHistory(model, out);
    out.statistics = statistics;
    return out;
  }
};

}  // namespace

double localErrorNorm(const Model& model, double h, const Eigen::VectorXd& a_start, const Eigen::VectorXd& a,
                      const Eigen::VectorXd& q, const ErrorTolerance& tolerance) {
  const double factor = h * h / 12.0;  // (LE), β − 1/6 = 1/12
  double norm = 0.0;
  for (int i : model.freeCoordinates())
    norm = std::max(norm, factor * std::abs(a[i] - a_start[i]) / (tolerance.absolute + tolerance.relative * std::abs(q[i])));
  return norm;
}

AdaptiveRun adaptiveNewmarkRun(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                               const Eigen::VectorXd& v0, const LocalErrorControl& control,
                               const std::function<void(double)>& progress) {
  if (!(control.tolerance.absolute > 0.0 && control.tolerance.relative >= 0.0))
    throw std::invalid_argument("the local tolerance needs a positive absolute part");
  if (settings.beta != 0.25 || settings.gamma != 0.5)
    throw std::invalid_argument("the adaptive integrator's error estimate is the trapezoidal rule's (beta = 0.25, gamma = 0.5)");
  const double end = settings.end_time;
  std::vector<double> stops;
  for (double t : control.stop_times)
    if (t > 0.0 && t < end * (1.0 - 1e-12) && (stops.empty() || t > stops.back())) stops.push_back(t);
  stops.push_back(end);
  NewmarkIntegrator integrator(model, settings);
  integrator.initialize(q0, v0, 0.0);
  GrowingTrajectory kept;
  kept.keep(integrator, 0);
  AdaptiveRun out;
  out.stops.push_back(0);
  double h = control.first_step > 0.0 ? control.first_step : std::min(settings.step, 0.01 * end);
  const double smallest = kSmallestStep * end;
  const double most_points = std::min(kMaxNewmarkSteps, kMaxTrajectoryBytes / bytesPerTimePoint(model, settings));
  std::size_t next_stop = 0;
  while (next_stop < stops.size()) {
    const double t = integrator.time(), stop = stops[next_stop];
    // Land on the stop exactly; split what is left in two rather than leave a sliver after a full step.
    const bool lands = t + h >= stop - 1e-12 * end;
    const double h_try = lands ? stop - t : (t + 2.0 * h > stop ? 0.5 * (stop - t) : h);
    if (!(h_try >= smallest))
      throw SimulationError(StepStatus::StepTooLarge, "the step controller's step fell below " + threeDigits(smallest) +
                                " s (the local error or Newton asks for ever smaller steps here)",
                            t, integrator.stepCount(), std::numeric_limits<double>::quiet_NaN(), "");
    if (const StepOutcome attempted = integrator.attemptStep(lands ? stop : t + h_try); !attempted.converged()) {
      if (!smallerStepMayHelp(attempted.status)) throw SimulationError(attempted);  // a loop that cannot close
      h = kAfterFailure * h_try;
      continue;
    }
    const double error =
        localErrorNorm(model, h_try, integrator.acceptedAcceleration(), integrator.a(), integrator.q(), control.tolerance);
    const double factor = std::clamp(error > 0.0 ? kSafety * std::cbrt(1.0 / error) : kLargest, kSmallest, kLargest);
    if (!(error <= 1.0)) {
      integrator.rejectStep();
      h = std::min(factor, kSafety) * h_try;
      continue;
    }
    if (const StepOutcome accepted = integrator.acceptStep(); !accepted.converged()) throw SimulationError(accepted);
    if (static_cast<double>(kept.time.size()) >= most_points)
      throw std::length_error("the adaptive run has taken " + std::to_string(kept.time.size()) + " steps by t = " +
                              threeDigits(integrator.time()) + " s of " + threeDigits(end) +
                              " s: its trajectory would exceed the limit of 4 GiB or 1e7 steps (kMaxTrajectoryBytes)");
    kept.keep(integrator, integrator.lastNewtonIterations());
    if (progress) progress(integrator.time());
    if (lands) {
      out.stops.push_back(static_cast<Eigen::Index>(kept.time.size() - 1));
      ++next_stop;
    }
    // After a step shortened to land on a stop, the step before it still holds where the error allows.
    h = lands && factor >= 1.0 ? std::max(h, factor * h_try) : factor * h_try;
  }
  out.trajectory = kept.finish(model, integrator.statistics());
  return out;
}

std::shared_ptr<const std::vector<double>> timeGrid(const Eigen::VectorXd& time) {
  return std::make_shared<const std::vector<double>>(time.data(), time.data() + time.size());
}

ErrorTolerance firstLocalTolerance(const ErrorTolerance& global) {
  // |e| ≈ K τ^{2/3}: τ = (ρ·kAcceptedFraction·TOL / K)^{3/2}, the relative part scaled alike.
  const double target = kStepSafety * kAcceptedFraction * global.absolute;
  const double absolute = std::pow(target / kGlobalErrorConstant, 1.0 / kGlobalPower);
  return {absolute, global.relative * absolute / global.absolute};
}

AccurateRun adaptiveToAccuracy(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                               const Eigen::VectorXd& v0, const AccuracyGoal& goal,
                               const std::function<void(double)>& progress) {
  if (!(goal.tolerance.absolute > 0.0 && goal.tolerance.relative >= 0.0))
    throw std::invalid_argument("the accuracy needs a positive absolute part and a relative part that is not negative");
  if (const std::string defect = halvingDefect(settings, "the adaptive integrator's error estimate"); !defect.empty())
    throw std::invalid_argument(defect);
  LocalErrorControl control;
  control.tolerance = firstLocalTolerance(goal.tolerance);
  // The global error goes as the local tolerance to a power p, 2/3 in theory (kGlobalPower) until two
  // attempts measure it.
  double power = kGlobalPower, previous_error = 0.0, previous_tolerance = 0.0;
  control.stop_times = outputTimes(goal.output_step, settings.end_time);
  NewmarkSettings run_settings = settings;
  run_settings.newton_tolerance = std::max(settings.newton_tolerance, kNewtonShareOfTolerance * goal.tolerance.absolute);
  AccurateRun out;
  IntegratorStatistics every_attempt;
  for (int attempt = 0; attempt < goal.max_attempts; ++attempt) {
    AccuracyAttempt record{0.0, 2, std::numeric_limits<double>::quiet_NaN(), {}};
    try {
      AdaptiveRun run = adaptiveNewmarkRun(model, run_settings, q0, v0, control, progress);
      NewmarkSettings grid = run_settings;
      grid.time_grid = timeGrid(run.trajectory.time);
      record.macro_step = largestStep(grid);
      EstimatedRun estimated = estimateGlobalError(model, grid, std::move(run.trajectory), q0, v0, progress);
      record.weighted_error = weightedErrorNorm(estimated.q_error, estimated.trajectory.q, goal.tolerance);
      addStatistics(every_attempt, estimated.trajectory.statistics);
      if (record.weighted_error <= kAcceptedFraction) {
        if (goal.output_step > 0.0) keepPoints(estimated, run.stops);
        estimated.trajectory.statistics = every_attempt;
        estimated.steps = {record.macro_step, 0.5 * record.macro_step};
        out.run = std::move(estimated);
        out.macro_step = record.macro_step;
        out.weighted_error = record.weighted_error;
        return out;
      }
      if (previous_error > 0.0)
        power = std::clamp(std::log(previous_error / record.weighted_error) /
                               std::log(previous_tolerance / control.tolerance.absolute), 0.5, 1.2);
      previous_error = record.weighted_error;
      previous_tolerance = control.tolerance.absolute;
      // Aim at kStepSafety of the accepted level.
      const double shrink =
          std::clamp(std::pow(kStepSafety * kAcceptedFraction / record.weighted_error, 1.0 / power), 1e-4, 0.5);
      control.tolerance.absolute *= shrink;
      control.tolerance.relative *= shrink;
    } catch (const SimulationError& e) {
      if (!smallerStepMayHelp(e.status)) throw;  // a check or a loop no tolerance is at fault for
      record.failure = e.what();
      control.tolerance.absolute *= 0.1;  // a failure of the controller itself: ask for smaller steps
      control.tolerance.relative *= 0.1;
      previous_error = 0.0;
    }
    out.rejected.push_back(record);
  }
  std::string message = "no adaptive run met the accuracy in " + std::to_string(goal.max_attempts) + " attempts";
  if (!out.rejected.empty()) {
    const AccuracyAttempt& last = out.rejected.back();
    message += last.failure.empty() ? "; the last reached " + threeDigits(last.weighted_error) + " times the tolerance"
                                    : "; the last failed: " + last.failure;
  }
  throw AccuracyError(message);
}

}  // namespace mbsopt
