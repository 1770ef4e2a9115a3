// The units of what mbsopt outputs: a coordinate's (m or rad) and a sensor's, SI, except that the
// reports give a relative angle in degrees (problems/scenes/README.md, "Sensors"). One table for
// every output that names a unit: the CSV header, the JSON records, the tables and the plot axes.
#pragma once

#include <string>

#include "mbsopt/model/model.hpp"

namespace mbsopt {

/// The unit of coordinate i (q; its rates per s, per s²): "rad" for a revolute joint, "m" for a
/// prismatic joint or a curve slider's arc length.
std::string coordinateUnit(const Model& model, int coordinate);

/// The SI unit of a model parameter by what it is: "kg", "m", "kg·m²" for a body's mass, centre and
/// moments; "m" or "rad" for an offset's translation or turn; "N/m", "N·m/rad", "N·s/m", "N·m·s/rad"
/// for a spring's stiffness and damping (by its joint's kind); a time input's coefficient c_k in its
/// value's unit per s^k, a harmonic's amplitude, angular frequency (rad/s) and phase (rad); "m/s²"
/// for gravity. Empty for a parameter of another kind (a track's numbers), which the reports call SI.
std::string parameterUnit(const Model& model, ParameterIndex parameter);

/// "name [unit]": how the CSV headers name a column.
std::string withUnit(const std::string& name, const std::string& unit);

/// The unit of a sensor's reported value: "m", "m/s", "m/s²", "rad", "rad/s", "rad/s²" for points and
/// joints, "deg" for a relative angle, "J" for an energy, "N" or "N·m" for a cut reaction.
std::string sensorUnit(const Model& model, const Sensor& sensor);

/// The SI unit of a sensor's value as the trajectories hold it (sensorUnit, but "rad" for a relative angle).
std::string sensorSiUnit(const Model& model, const Sensor& sensor);

/// Whether the reports give the sensor in degrees (a relative angle).
bool isAngle(const Sensor& sensor);
/// Whether the sensor's value is an angle in radians in SI (a relative angle, or a revolute joint's
/// position): what a bound written in degrees may constrain.
bool measuresAngle(const Model& model, const Sensor& sensor);
/// A sensor's SI value in the reports' unit: degrees for a relative angle, its own otherwise.
double inUnits(const Sensor& sensor, double value);

}  // namespace mbsopt
