// Runs driven by accuracy (docs/integrators.md): the macro step H and the number of
// extrapolated runs are chosen so that the estimated global error of the coordinates meets a
// tolerance, weighted per entry as IDA weights it (|e| ≤ absolute + relative·|q|).
//
// One attempt runs Newmark at H/1, H/2, … and adds each to an ExtrapolationTableau. After run j ≥ 2
// the weighted estimate err_j of the result T_{j,j−1} (order p_{j−1}) is known:
//   - err_j ≤ kAcceptedFraction: the run is accepted;
//   - otherwise the macro step that would meet it with j runs is H_j = H (kAcceptedFraction·ρ / err_j)^{1/p_{j−1}}
//     (ρ = kStepSafety), at a work of (1 + 2 + … + j) / H_j steps per unit time;
//   - the attempt goes on to j + 1 while the estimates fall, up to max_runs; when they stop falling
//     (the expansion does not hold yet at this H) or max_runs is reached, the next attempt takes the
//     cheapest H_j (and at most that j + 1 runs), never more than 0.9 H.
// The estimate does not see the round-off the weights amplify: once an attempt of kProbedRuns runs or
// more is accepted on its truncation error, and Newton runs at the scene's own tolerance (a tolerance
// of 1e-7 or less with the default 1e-10), its runs 2 … j are repeated a few ulps of step longer
// (ExtrapolationTableau::addRoundOffProbe) and the measured floor is added to err_j. When that rejects
// it, H_j is where err_j (H_j/H)^p plus the floor, grown as H/H_j (a run's round-off grows as its step
// falls), meets the level aimed at; a j for which no H_j does is not tried again (fewer runs, smaller
// weights), and when none does the run stops with AccuracyError: the tolerance is below the round-off.
// A run that fails (Newton does not converge, a singular iteration matrix, a check after a step)
// means H was too large for Newton: the next attempt takes H / 2, and the message of the failure is
// kept. Newton's tolerance follows the accuracy asked for (kNewtonShareOfTolerance), as SUNDIALS ties
// its nonlinear solver's to the error test: at loose tolerances most of a large step's iterations
// would otherwise chase 1e-10. After max_attempts, or below min_step, AccuracyError says what the best attempt reached.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/integrators/extrapolation.hpp"

namespace mbsopt {

struct AccuracyGoal {
  ErrorTolerance tolerance;
  /// The result's time points are the multiples of uniformStep(output_step, end_time) [s] (H then
  /// divides it); 0: the multiples of the macro step the run chooses.
  double output_step = 0.0;
  /// Runs per attempt at most: 2 gives a plain Newmark run at H/2 (order 2) with its estimate; more
  /// give extrapolated results of higher order.
  int max_runs = 6;
  int max_attempts = 12;
  /// The first attempt's macro step [s]; 0: the end time / kFirstMacroSteps (at most the output step).
  double first_macro_step = 0.0;
};

/// An attempt that was not accepted, and why.
struct AccuracyAttempt {
  double macro_step = 0.0;
  int runs = 0;                  ///< runs made
  double weighted_error = 0.0;   ///< the last estimate (relative to the tolerance); NaN after a failure
  std::string failure;           ///< the failed run's message, or empty
};

struct AccurateRun {
  EstimatedRun run;             ///< the accepted result and its estimated errors
  double macro_step = 0.0;      ///< H of the accepted attempt
  double weighted_error = 0.0;  ///< its estimate relative to the tolerance: at most kAcceptedFraction
  std::vector<AccuracyAttempt> rejected;  ///< the attempts before it
};

/// A run is accepted when its weighted estimate is at most this: the estimate is within a factor
/// of about 2 of the true error (docs/integrators.md), so the true error stays below the tolerance.
inline constexpr double kAcceptedFraction = 0.5;
/// Newton's tolerance in a run driven by accuracy: at least this fraction of the absolute tolerance
/// (and never below the scene's own). Its error in q̈, a fraction of it per step, stays below the
/// tolerance after the combination's weights (Σ|c_i| = 57 for the result of 6 runs with cut joints) and T² scale it.
inline constexpr double kNewtonShareOfTolerance = 1e-3;
/// The next attempt aims at this fraction of the accepted level.
inline constexpr double kStepSafety = 0.7;
/// Where a round-off floor was measured, the steps that would be accepted with each number of runs are
/// sought up to this many times this attempt's macro step (the next attempt takes at most 0.9 times it).
inline constexpr double kLargestStepGrowth = 4.0;

/// The first attempt's macro step is the end time over this (at most the output step): coarse, so
/// that its runs cost little, and refined from their estimates.
inline constexpr double kFirstMacroSteps = 64.0;

/// A number with three significant digits, as the controllers' messages print it.
std::string threeDigits(double value);
/// The multiples of uniformStep(output_step, end_time) before `end_time` (the run's end is a time
/// point anyway); none for an output step of 0.
std::vector<double> outputTimes(double output_step, double end_time);
/// No attempt reached the goal: says what the best one reached.
class AccuracyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The scene run (its end time, β = 1/4, γ = 1/2, its Newton and closure settings; settings.step is
/// not used) until its estimated global error meets the goal. `progress(t, attempt)` after each step of every run.
AccurateRun simulateToAccuracy(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                               const Eigen::VectorXd& v0, const AccuracyGoal& goal,
                               const std::function<void(double)>& progress = {});

}  // namespace mbsopt
