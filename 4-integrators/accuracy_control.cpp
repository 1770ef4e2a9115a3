#include "mbsopt/integrators/accuracy_control.hpp"

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
double onOutputGrid(double H, double output_step) { return output_step > 0.0 ? uniformStep(H, output_step) : H; }

/// The round-off floor of the result of `runs` runs, weighted as its estimate (zero without a probe).
double weightedFloor(const ExtrapolationTableau& tableau, int runs, const ErrorTolerance& tolerance) {
  if (!tableau.probed()) return 0.0;
  const SampledRun repeated = tableau.repeatedResult(runs);
  return weightedErrorNorm(tableau.roundOffFloor(&SampledRun::q, runs), repeated.q, tolerance);
}

/// The macro step, as a fraction x of this one, at which a result whose weighted truncation error is
/// `truncation` x^order and whose round-off floor is `floor`/x (a run's round-off grows as its step
/// falls: docs/integrators.md §5) meets `target`: the largest such x up to `largest`, 0 where none does.
double fittingStepFraction(double truncation, double floor, int order, double target, double largest) {
  if (floor <= 0.0) return std::pow(target / truncation, 1.0 / order);
  const auto total = [&](double x) { return truncation * std::pow(x, order) + floor / x; };
  if (total(largest) <= target) return largest;
  // The smallest total is at x* = (floor / (order · truncation))^{1/(order+1)}; above it the total grows.
  double low = std::pow(floor / (order * truncation), 1.0 / (order + 1)), high = largest;
  if (low >= largest || total(low) > target) return 0.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (low + high);
    (total(mid) <= target ? low : high) = mid;
  }
  return low;
}

}  // namespace

std::vector<double> outputTimes(double output_step, double end_time) {
  std::vector<double> times;
  if (!(output_step > 0.0)) return times;
  const long outputs = stepsToCover(end_time, output_step);
  const double interval = end_time / static_cast<double>(outputs);
  for (long m = 1; m < outputs; ++m) times.push_back(static_cast<double>(m) * interval);
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
  const double output_step = goal.output_step > 0.0 ? uniformStep(goal.output_step, settings.end_time) : 0.0;
  double H = settings.end_time / kFirstMacroSteps;  // coarse: cheap, and refined from its estimate
  if (output_step > 0.0) H = std::min(H, output_step);
  if (goal.first_macro_step > 0.0) H = goal.first_macro_step;
  int max_runs = goal.max_runs;
  int floor_cap = goal.max_runs;  // the most runs whose round-off floor leaves room for the truncation error
  bool floor_limited = false;     // no number of runs leaves room: the tolerance is below the round-off
  AccurateRun out;
  IntegratorStatistics every_attempt;
  for (int attempt = 0; attempt < goal.max_attempts && H >= min_step; ++attempt) {
    H = uniformStep(onOutputGrid(H, output_step), settings.end_time);  // the last macro step ends at T
    NewmarkSettings macro = settings;
    macro.step = H;
    macro.newton_tolerance = std::max(settings.newton_tolerance, kNewtonShareOfTolerance * goal.tolerance.absolute);
    const long outputs = stepsToCover(settings.end_time, H);
    // Newton stopped above the scene's tolerance leaves errors of a 1e-3 share of the accuracy
    // (kNewtonShareOfTolerance), far above the round-off, and where it stops flips with the last bits:
    // a probe would measure that, not the rounding.
    const bool probesRoundOff = macro.newton_tolerance <= settings.newton_tolerance;
    ExtrapolationTableau tableau(exponents);
    AccuracyAttempt record{H, 0, std::numeric_limits<double>::quiet_NaN(), {}};
    std::vector<double> truncation;  // the weighted estimate of the result of j runs, j = 2 … record.runs
    for (int j = 1; j <= max_runs; ++j) {
      NewmarkSettings run = macro;
      run.step = H / j;
      try {
        tableau.add(sampledNewmarkRun(model, run, q0, v0, j, outputs, progress), run.step);
      } catch (const SimulationError& e) {
        if (!smallerStepMayHelp(e.status)) throw;  // a check or a loop no step size is at fault for
        record.failure = e.what();
        break;
      }
      record.runs = j;
      if (j < 2) continue;
      const SampledRun result = tableau.result();
      const Eigen::MatrixXd estimate = (tableau.check().q - result.q).cwiseAbs();
      truncation.push_back(weightedErrorNorm(estimate, result.q, goal.tolerance));
      double error = truncation.back();
      // Accepted on its truncation error: the round-off its weights amplify decides (kProbedRuns runs
      // or more, Newton at the scene's own tolerance).
      if (error <= kAcceptedFraction && j >= kProbedRuns && probesRoundOff && !tableau.probed()) {
        try {
          tableau.addRoundOffProbe(roundOffProbe(model, macro, j, q0, v0, outputs, progress));
        } catch (const SimulationError& e) {
          if (!smallerStepMayHelp(e.status)) throw;
          record.failure = e.what();
          break;
        }
      }
      if (tableau.probed()) error = weightedErrorNorm(estimate + tableau.roundOffFloor(&SampledRun::q), result.q, goal.tolerance);
      record.weighted_error = error;
      if (error <= kAcceptedFraction) {
        addStatistics(every_attempt, tableau.statistics());
        out.run = estimatedRun(model, macro, tableau);
        out.run.trajectory.statistics = every_attempt;
        out.macro_step = H;
        out.weighted_error = error;
        return out;
      }
      if (tableau.probed()) break;  // rejected by its round-off: more runs would only add to it
      if (j >= 3 && !(truncation.back() < truncation[truncation.size() - 2])) break;  // the expansion does not hold yet at this H
    }
    addStatistics(every_attempt, tableau.statistics());
    out.rejected.push_back(record);
    if (!record.failure.empty()) {
      H /= 2.0;  // a step too large for Newton (or for a check after it)
      continue;
    }
    // The result of j runs errs as H^p plus its round-off floor (measured when probed; as 1/H at
    // other steps): the H that would be accepted with j runs, and its work. Few runs fit no step where
    // the floor grows faster than their order cuts the truncation error, many where their weights
    // make it large: the most runs that fit bound the next attempts.
    double best_work = std::numeric_limits<double>::infinity(), next_step = 0.0;
    int next_runs = 2, most_fitting = 0;
    for (int j = 2; j <= record.runs; ++j) {
      const int order = exponents[static_cast<std::size_t>(j - 2)];
      // The safety is on the truncation error's prediction: the floor is measured again where it is accepted.
      const double x = fittingStepFraction(truncation[static_cast<std::size_t>(j - 2)] / kStepSafety,
                                           weightedFloor(tableau, j, goal.tolerance), order, kAcceptedFraction,
                                           kLargestStepGrowth);
      if (x <= 0.0) continue;
      most_fitting = j;
      const double work = 0.5 * j * (j + 1) / (x * H);
      if (work < best_work) best_work = work, next_step = x * H, next_runs = j;
    }
    if (tableau.probed() && most_fitting > 0) floor_cap = std::min(floor_cap, std::max(most_fitting, 2));
    if (next_step <= 0.0) {
      floor_limited = true;  // not even a plain run's round-off leaves room for the tolerance
      break;
    }
    H = std::min(next_step, 0.9 * H);
    max_runs = std::min({goal.max_runs, floor_cap, next_runs + 1});
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
  if (floor_limited)
    what += "; the runs' round-off (measured by repeating them a few ulps of step longer) leaves no room for "
            "the truncation error at any step with " + std::to_string(out.rejected.back().runs) + " runs or fewer";
  else if (H < min_step)
    what += "; the next macro step, " + threeDigits(H) + " s, would take more than 1e7 steps";
  if (!out.rejected.empty() && !out.rejected.back().failure.empty()) what += "; the last run failed: " + out.rejected.back().failure;
  throw AccuracyError(what);
}

}  // namespace mbsopt
