#include "mbsopt/dynamics/units.hpp"

#include <numbers>
#include <variant>

#include "mbsopt/dynamics/overloaded.hpp"

namespace mbsopt {

namespace {

/// m, m/s, m/s² (or rad, …) for a sensed position, velocity, acceleration.
std::string derivativeUnit(Derivative d, bool angular) {
  const std::string base = angular ? "rad" : "m";
  return d == Derivative::Position ? base : d == Derivative::Velocity ? base + "/s" : base + "/s²";
}

/// Whether coordinate i is a revolute joint's angle.
bool isRevolute(const Model& model, int coordinate) {
  const KinematicElement& joint =
      model.elements()[static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(coordinate)].element)];
  return std::holds_alternative<RevoluteJoint>(joint.kind);
}

}  // namespace

std::string coordinateUnit(const Model& model, int coordinate) { return isRevolute(model, coordinate) ? "rad" : "m"; }

std::string withUnit(const std::string& name, const std::string& unit) { return name + " [" + unit + "]"; }

std::string sensorSiUnit(const Model& model, const Sensor& sensor) {
  return std::visit(
      Overloaded{[](const PointSensor& s) -> std::string { return derivativeUnit(s.quantity, false); },
                 [&](const JointSensor& s) -> std::string { return derivativeUnit(s.quantity, isRevolute(model, s.coordinate)); },
                 [](const RelativeAngleSensor&) -> std::string { return "rad"; },
                 [](const EnergySensor&) -> std::string { return "J"; },
                 [](const CutReactionSensor& s) -> std::string {
                   return s.quantity == ReactionQuantity::Force ? "N" : "N·m";
                 }},
      sensor.kind);
}

std::string sensorUnit(const Model& model, const Sensor& sensor) {
  return isAngle(sensor) ? "deg" : sensorSiUnit(model, sensor);
}

bool isAngle(const Sensor& sensor) { return std::holds_alternative<RelativeAngleSensor>(sensor.kind); }

bool measuresAngle(const Model& model, const Sensor& sensor) { return sensorSiUnit(model, sensor) == "rad"; }

double inUnits(const Sensor& sensor, double value) { return isAngle(sensor) ? value * 180.0 / std::numbers::pi : value; }

}  // namespace mbsopt
