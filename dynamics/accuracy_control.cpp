#include "mbsopt/dynamics/accuracy_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mbsopt {

namespace {

void requireGoal(const AccuracyGoal& goal) {
  const ErrorTolerance& t = goal.tolerance;
  if (!(t.absolute >= 0.0 && t.relative >= 0.0 && std::isfinite(t.absolute) && std::isfinite(t.relative)) ||
      !(t.absolute > 0.0))
    throw std::invalid_argument("the accuracy needs a positive absolute part and a relative part that is not negative");
  if (!(goal.output_step >= 0.0 && std::isfinite(goal.output_step)))
    throw std::invalid_argument("the output step must be positive and finite");
  if (goal.max_runs < 2) throw std::invalid_argument("a run driven by accuracy needs at least 2 runs per attempt");
  if (goal.max_attempts < 1) throw std::invalid_argument("a run driven by accuracy needs at least one attempt");
  if (!(goal.first_macro_step >= 0.0 && std::isfinite(goal.first_macro_step)))
    throw std::invalid_argument("the first macro step must be positive and finite");
}

/// H, or the largest step at most H that divides the output step into whole steps.
double onOutputGrid(double H, double output_step) {
  if (!(output_step > 0.0)) return H;
  return output_step / std::ceil(output_step / H - 1e-9);
}

}  // namespace

std::vector<double> outputTimes(double output_step, double end_time) {
  std::vector<double> times;
  if (output_step > 0.0)
    for (long m = 1; static_cast<double>(m) * output_step < end_time * (1.0 - 1e-12); ++m)
      times.push_back(static_cast<double>(m) * output_step);
  return times;
}

std::string threeDigits(double value) {
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

AccurateRun simulateToAccuracy(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                               const Eigen::VectorXd& v0, const AccuracyGoal& goal,
                               const std::function<void(double)>& progress) {
  requireGoal(goal);
  if (const std::string defect = extrapolationDefect(settings); !defect.empty()) throw std::invalid_argument(defect);
  const std::vector<int> exponents = errorExponents(model, settings);
  // The smallest macro step worth an attempt: its finest run would take kMaxNewmarkSteps.
  const double min_step = settings.end_time * goal.max_runs / kMaxNewmarkSteps;
  double H = settings.end_time / kFirstMacroSteps;  // coarse: cheap, and refined from its estimate
  if (goal.output_step > 0.0) H = std::min(H, goal.output_step);
  if (goal.first_macro_step > 0.0) H = goal.first_macro_step;
  int max_runs = goal.max_runs;
  AccurateRun out;
  IntegratorStatistics every_attempt;
  for (int attempt = 0; attempt < goal.max_attempts && H >= min_step; ++attempt) {
    H = onOutputGrid(H, goal.output_step);
    NewmarkSettings macro = settings;
    macro.step = H;
    macro.newton_tolerance = std::max(settings.newton_tolerance, kNewtonShareOfTolerance * goal.tolerance.absolute);
    const long outputs = stepsToCover(settings.end_time, H);
    ExtrapolationTableau tableau(exponents);
    AccuracyAttempt record{H, 0, std::numeric_limits<double>::quiet_NaN(), {}};
    double previous = std::numeric_limits<double>::infinity(), best_work = previous, next_step = 0.5 * H;
    int next_runs = max_runs;
    for (int j = 1; j <= max_runs; ++j) {
      NewmarkSettings run = macro;
      run.step = H / j;
      try {
        tableau.add(sampledNewmarkRun(model, run, q0, v0, j, outputs, progress), run.step);
      } catch (const SimulationError& e) {
        record.failure = e.what();
        break;
      }
      record.runs = j;
      if (j < 2) continue;
      const SampledRun result = tableau.result();
      const double error = weightedErrorNorm(tableau.check().q - result.q, result.q, goal.tolerance);
      record.weighted_error = error;
      if (error <= kAcceptedFraction) {
        addStatistics(every_attempt, tableau.statistics());
        out.run = estimatedRun(model, macro, tableau);
        out.run.trajectory.statistics = every_attempt;
        out.macro_step = H;
        out.weighted_error = error;
        return out;
      }
      // The result's error scales as H^p: the H that would be accepted with j runs, and its work.
      const int order = exponents[static_cast<std::size_t>(j - 2)];
      const double step = H * std::pow(kAcceptedFraction * kStepSafety / error, 1.0 / order);
      const double work = 0.5 * j * (j + 1) / step;
      if (work < best_work) {
        best_work = work;
        next_step = step;
        next_runs = j;
      }
      if (j >= 3 && !(error < previous)) break;  // the expansion does not hold yet at this H
      previous = error;
    }
    addStatistics(every_attempt, tableau.statistics());
    out.rejected.push_back(record);
    if (!record.failure.empty()) {
      H /= 2.0;  // a step too large for Newton (or for a check after it)
      continue;
    }
    H = std::min(next_step, 0.9 * H);
    max_runs = std::min(goal.max_runs, next_runs + 1);
  }
  std::string what = "no run met the accuracy (absolute " + threeDigits(goal.tolerance.absolute) + ", relative " +
                     threeDigits(goal.tolerance.relative) + ") in " + std::to_string(out.rejected.size()) + " attempts";
  double best = std::numeric_limits<double>::infinity();
  const AccuracyAttempt* closest = nullptr;
  for (const AccuracyAttempt& a : out.rejected)
    if (a.weighted_error < best) best = a.weighted_error, closest = &a;
  if (closest)
    what += "; the closest estimated " + threeDigits(best) + " times the tolerance, at macro step " +
            threeDigits(closest->macro_step) + " s with " + std::to_string(closest->runs) + " runs";
  if (H < min_step) what += "; the next macro step, " + threeDigits(H) + " s, would take more than 1e7 steps";
  if (!out.rejected.empty() && !out.rejected.back().failure.empty()) what += "; the last run failed: " + out.rejected.back().failure;
  throw AccuracyError(what);
}

}  // namespace mbsopt
