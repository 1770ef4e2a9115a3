// Where the motion's accelerations jump, and a time grid that steps across those times in tiny steps.
//
// A curve slider that passes the end of a circular arc (into a straight, or an arc of another radius)
// feels its track's curvature jump: the acceleration of its frame jumps by v² Δκ, and every coordinate's
// acceleration with it. A Newmark step across such a time integrates a discontinuous q̈ with the
// trapezoidal rule, an error of order h Δq̈ in q̇ that the run carries to its end: the global error
// falls as h, not h². Steps that cross the jump in one step of length η ≪ h (docs/integrators.md §11)
// leave an error of order η Δq̈ and the rest of the run second order again.
#pragma once

#include <memory>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {

/// Whether a curve slider of `model` rides a track whose curvature jumps somewhere.
bool hasCurvatureJumps(const Model& model);

/// The times at which a curve slider of `model` (driven, free or a cut's) passes a point of its track
/// where the curvature jumps, read off a run's trajectory: each crossing located on the cubic through
/// the two time points around it (their q and q̇, an error of order h⁴ in the arc length). Sorted.
std::vector<double> curvatureJumpTimes(const Model& model, const Trajectory& trajectory);

/// The crossing step around a break time: η = h²/T (T the end time), at most h/16. Its error,
/// of order η Δq̈ in q̇, then falls as h² like the rest of the run's.
double crossingStep(double step, double end_time);

/// A time grid (NewmarkSettings::time_grid) of steps uniformStep(step, end_time) up to `end_time`,
/// except around each time in `breaks` (0 < t < end_time): there one step of length crossingStep() of
/// that step centred on the break, and steps that double away from it up to that step.
std::shared_ptr<const std::vector<double>> gradedTimeGrid(double step, double end_time,
                                                         const std::vector<double>& breaks);

}  // namespace mbsopt
