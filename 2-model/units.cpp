#include "mbsopt/model/units.hpp"

#include <algorithm>
#include <iterator>
#include <numbers>
#include <variant>

#include "mbsopt/model/overloaded.hpp"

namespace mbsopt {

namespace {

/// m, m/s, m/s² (or rad, …) for a sensed position, velocity, acceleration.
std::string derivativeUnit(Derivative d, bool angular) {
  const std::string base = angular ? "rad" : "m";
  return d == Derivative::Position ? base : d == Derivative::Velocity ? base + "/s" : base + "/s²";
}

/// Whether coordinate i is an angle: a revolute joint's or a component of a ball joint's rotation vector.
bool isAngularCoordinate(const Model& model, int coordinate) {
  const KinematicElement& joint =
      model.elements()[static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(coordinate)].element)];
  return std::holds_alternative<RevoluteJoint>(joint.kind) || std::holds_alternative<BallJointComponent>(joint.kind);
}

/// The unit of `parameter` where it is one of the time input's numbers, its value in `unit`; empty otherwise.
std::string timeInputUnit(const TimeInput& input, const std::string& unit, ParameterIndex parameter) {
  static const char* const kPerSecond[] = {"", "/s", "/s²", "/s³"};
  for (std::size_t k = 0; k < input.coefficients.size(); ++k)
    if (input.coefficients[k] == parameter)
      return k < std::size(kPerSecond) ? unit + kPerSecond[k] : unit + "/s^" + std::to_string(k);
  for (const auto& [amplitude, angular_frequency, phase] : input.harmonics) {
    if (amplitude == parameter) return unit;
    if (angular_frequency == parameter) return "rad/s";
    if (phase == parameter) return "rad";
  }
  return "";
}

bool contains(const ParameterVector3& vector, ParameterIndex parameter) {
  return std::find(vector.begin(), vector.end(), parameter) != vector.end();
}

/// A force element's parameter's unit; empty where it is not one of the element's.
std::string forceParameterUnit(const Model& model, const ForceElement& force, ParameterIndex p) {
  const auto spring = [&](ParameterIndex stiffness, ParameterIndex damping, bool angular) -> std::string {
    const std::string q = angular ? "rad" : "m", load = angular ? "N·m" : "N";
    if (stiffness == p) return load + "/" + q;
    if (damping == p) return load + "·s/" + q;
    return "";
  };
  return std::visit(
      Overloaded{[&](const JointSpringDamper& s) {
                   const bool angular = isAngularCoordinate(model, s.coordinate);
                   const std::string unit = spring(s.stiffness, s.damping, angular);
                   return unit.empty() ? timeInputUnit(s.rest, angular ? "rad" : "m", p) : unit;
                 },
                 [&](const PointSpringDamper& s) {
                   return s.rest_length == p ? std::string("m") : spring(s.stiffness, s.damping, false);
                 },
                 [&](const JointActuation& a) {
                   return timeInputUnit(a.force, isAngularCoordinate(model, a.coordinate) ? "N·m" : "N", p);
                 },
                 [&](const TrackGuidance& g) { return spring(g.stiffness, g.damping, true); },
                 [&](const RotationalDamper& d) { return d.damping == p ? std::string("N·m·s/rad") : std::string(); }},
      force);
}

}  // namespace

std::string parameterUnit(const Model& model, ParameterIndex parameter) {
  for (const Body& body : model.bodies()) {
    if (body.mass == parameter) return "kg";
    if (contains(body.centre_of_mass, parameter)) return "m";
    if (contains(body.moments_of_inertia, parameter)) return "kg·m²";
  }
  for (const KinematicElement& element : model.elements())
    if (const auto* offset = std::get_if<Offset>(&element.kind)) {
      if (contains(offset->translation, parameter)) return "m";
      if (offset->turn && offset->turn->angle == parameter) return "rad";
    }
  if (contains(model.gravityParameters(), parameter)) return "m/s²";
  for (const JointArmature& armature : model.armatures())
    if (armature.inertia == parameter) return isAngularCoordinate(model, armature.coordinate) ? "kg·m²" : "kg";
  for (const ForceElement& force : model.forces())
    if (std::string unit = forceParameterUnit(model, force, parameter); !unit.empty()) return unit;
  for (std::size_t i = 0; i < model.coordinates().size(); ++i)
    if (std::string unit = timeInputUnit(model.coordinates()[i].motion, coordinateUnit(model, static_cast<int>(i)), parameter);
        !unit.empty())
      return unit;
  return "";
}

std::string coordinateUnit(const Model& model, int coordinate) { return isAngularCoordinate(model, coordinate) ? "rad" : "m"; }

std::string withUnit(const std::string& name, const std::string& unit) { return name + " [" + unit + "]"; }

std::string sensorSiUnit(const Model& model, const Sensor& sensor) {
  return std::visit(
      Overloaded{[](const PointSensor& s) -> std::string { return derivativeUnit(s.quantity, false); },
                 [&](const JointSensor& s) -> std::string { return derivativeUnit(s.quantity, isAngularCoordinate(model, s.coordinate)); },
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
