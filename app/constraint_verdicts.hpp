// Each constraint of a design problem judged at a design in its sensor's own units, whatever the
// transcription the optimizer saw: the verdict "feasible" of the commands.
#pragma once

#include <string>
#include <vector>

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

/// The verdict of every constraint of the problem, in every load case, on the response's trajectories.
std::vector<ConstraintVerdict> constraintVerdicts(const DesignProblem& problem, const DesignResponse& response);

/// The unit of a sensor's value as the verdicts and reports give it ("m", "rad/s", "deg", "N", …).
std::string sensorUnit(const Model& model, const Sensor& sensor);

/// The unit of a measure of a sensor as the reports give it: sensorUnit, times s for an integral.
std::string measureUnit(const Model& model, const Sensor& sensor, ResponseMeasure of);

/// Whether the reports give the sensor in degrees (a relative angle).
bool isAngle(const Sensor& sensor);
/// A sensor's SI value in the reports' unit: degrees for an angle, its own otherwise.
double inUnits(const Sensor& sensor, double value);

}  // namespace mbsopt
