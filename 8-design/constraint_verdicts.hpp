// Each constraint of a design problem judged at a design in its sensor's own units, whatever the
// transcription the optimizer saw: the verdict "feasible" of the commands.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/model/units.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

struct ConstraintVerdict {
  std::string name;  ///< SENSOR_OF, with _CASE under load cases: yaw_front_max_abs, x_final_fast
  /// The unit of value, bound, excess and tolerance: the sensor's (angles in deg), ·s for an integral.
  std::string unit;
  double value = 0.0;  ///< max |y|, max y, min y, ∫y dt, y(τ) or the RMS, on the time grid
  double bound = 0.0;  ///< the bound, or the value an equality asks for
  bool equality = false;
  /// How far the value lies beyond the bound: value − bound (bound − value for a minimum,
  /// |value − bound| for an equality); ≤ 0 inside.
  double excess = 0.0;
  /// The constraint's own `tolerance:`, or 1e-4 |bound| and at least 1e-6 in SI units.
  double tolerance = 0.0;
  bool met() const { return excess <= tolerance; }
};

/// The default tolerance of a constraint in the reports: a relative 1e-4 of the bound (1e-3° on a 10°
/// limit), at least 1e-6 in SI units (the optimizers' feasibility tolerance on a transcribed value).
inline constexpr double kRelativeTolerance = 1e-4, kAbsoluteTolerance = 1e-6;
/// How far a constraint's value may lie beyond its bound in the reports [SI]: its own `tolerance:`, or
/// the default.
double constraintTolerance(const ResponseConstraint& constraint);

/// SENSOR_OF: the name of a constraint in the reports (yaw_front_max_abs), before any load case's suffix.
std::string constraintName(const ResponseConstraint& constraint);

/// The verdict of every constraint of the problem, in every load case, on the response's trajectories.
std::vector<ConstraintVerdict> constraintVerdicts(const DesignProblem& problem, const DesignResponse& response);

/// The largest excess over its tolerance among the verdicts (≤ 1: every one met; 0 without any):
/// NlpEvaluation::excess_over_tolerance of a design problem.
double excessOverTolerance(const std::vector<ConstraintVerdict>& verdicts);

/// The unit of a measure of a sensor as the reports give it: sensorUnit, times s for an integral.
std::string measureUnit(const Model& model, const Sensor& sensor, ResponseMeasure of);

}  // namespace mbsopt
