// The trapezoidal Newmark scheme at variable steps with local error control
// (docs/integrators.md §4).
//
// Each step's local error in the coordinates is estimated as Zienkiewicz and Xie do for the Newmark
// family ("A simple error estimator and adaptive time stepping procedure for dynamic analysis",
// Earthquake Eng. Struct. Dyn. 20, 1991): from the Taylor expansion of the update of q,
//     e = (β − 1/6) h² (q̈ₙ₊₁ − q̈ₙ) = h³/12 q⃛ + O(h⁴)   (β = 1/4, the trapezoidal rule)     (LE)
// (Newton's q̈ₙ₊₁ before the projections, on the free coordinates). A step is accepted when the
// weighted max-norm of e is at most 1, and the next one is h·clamp(0.9 err^{−1/3}, 0.2, 2); a step that
// Newton cannot solve is retried at h/4. The velocities' local error (h³/12 q⁗) is not controlled:
// weighting it into the norm as an ODE solver weights its state cost 1.5-3 times more steps for the
// same global error on Andrews' squeezer, and the global estimate below covers both.
//
// The global error of such a run is estimated as for a fixed step: the same step sequence halved
// (each step split in two) is an asymptotically smooth refinement of the mesh, so the error again
// falls by 4: e_h = 4/3 (y_h − y_{h/2}) (estimateGlobalError). A run driven by accuracy tightens the
// local tolerance until that estimate meets the goal (adaptiveToAccuracy).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "mbsopt/integrators/accuracy_control.hpp"
#include "mbsopt/integrators/extrapolation.hpp"

namespace mbsopt {

struct LocalErrorControl {
  /// What each step's local error (LE) in the coordinates may be.
  ErrorTolerance tolerance;
  /// The first step [s]; 0: the scene's step, at most a hundredth of the end time (the controller
  /// doubles it each step while the error allows, and rejects it when it is too large).
  double first_step = 0.0;
  /// Steps end exactly at these times (output times, known discontinuities), increasing, in (0, end].
  std::vector<double> stop_times;
};

/// An adaptive run: every accepted step, and where its stop times are.
struct AdaptiveRun {
  Trajectory trajectory;             ///< every accepted step, with the sensors
  std::vector<Eigen::Index> stops;   ///< the trajectory's points at t = 0 and at each stop time, in order
};

/// (LE) weighted: max over the free coordinates of |h²/12 (a − a_start)| / (absolute + relative |q|).
double localErrorNorm(const Model& model, double h, const Eigen::VectorXd& a_start, const Eigen::VectorXd& a,
                      const Eigen::VectorXd& q, const ErrorTolerance& tolerance);

/// Runs from (q0, v0) at t = 0 to settings.end_time with steps chosen by the local error (settings.step
/// is not used). SimulationError when a step fails below the smallest step (end time × 1e-12) or a
/// check after a step fails; std::length_error beyond kMaxNewmarkSteps steps or kMaxTrajectoryBytes.
AdaptiveRun adaptiveNewmarkRun(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                               const Eigen::VectorXd& v0, const LocalErrorControl& control,
                               const std::function<void(double)>& progress = {});

/// The time points of a run as a grid NewmarkSettings::time_grid replays.
std::shared_ptr<const std::vector<double>> timeGrid(const Eigen::VectorXd& time);

/// The global error of a run whose local errors are held to τ goes as K τ^{2/3}: the steps as τ^{1/3}
/// ((LE) is O(h³)), the error as their square. Measured (max over the output times) 0.6-0.8 for the
/// power on the four-bar and Andrews' squeezer from τ = 1e-5 to 1e-9.
inline constexpr double kGlobalPower = 2.0 / 3.0;
/// K [unit^{1/3}] of the first attempt: measured 22-39 on the four-bar, 8-16 on Andrews' squeezer.
inline constexpr double kGlobalErrorConstant = 20.0;
/// The local tolerance of the first attempt at a global goal: K τ^{2/3} = kStepSafety·kAcceptedFraction·TOL.
ErrorTolerance firstLocalTolerance(const ErrorTolerance& global);

/// An adaptive run whose estimated global error meets the goal (its tolerance, output step,
/// max_attempts): the local tolerance starts at firstLocalTolerance and is tightened from each attempt's
/// estimate (by kGlobalPower, then by the power two attempts measured) until the weighted estimate is at
/// most kAcceptedFraction. The result's time points are the multiples of the
/// goal's output step when it has one (the steps end there), else every step; AccurateRun::macro_step
/// is the largest step taken. AccuracyError when no attempt meets it.
AccurateRun adaptiveToAccuracy(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                               const Eigen::VectorXd& v0, const AccuracyGoal& goal,
                               const std::function<void(double)>& progress = {});

}  // namespace mbsopt
