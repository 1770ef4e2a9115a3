#include "mbsopt/algorithms/sensors.hpp"

#include <cmath>
#include <stdexcept>

#include "mbsopt/model/overloaded.hpp"
#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/energy.hpp"

namespace mbsopt {

namespace {

/// An energy or cut-reaction sensor at one time point; ws holds the kinematics of the state.
double systemSensorValue(const Model& model, const Sensor& sensor, const Workspace<double>& ws,
                         const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                         const Eigen::VectorXd& lambda, double t) {
  if (const auto* energy = std::get_if<EnergySensor>(&sensor.kind))
    return energyPart(mechanicalEnergyOfFrames(model, ws, q, v, t), energy->part);
  if (lambda.size() != model.constraintCount())
    throw std::invalid_argument("sensor '" + sensor.name + "': the trajectory holds no multipliers λ of the cuts");
  return sensorValue(model, sensor, ws, q, v, a, lambda);
}

template <class Scalar>
[[noreturn]] Scalar notAStateSensor(const Sensor& sensor) {
  throw std::invalid_argument("sensor '" + sensor.name +
                              "' is not a function of the state (q, q̇, q̈) alone: sensorHistory evaluates it");
}

}  // namespace

bool isStateSensor(const Sensor& sensor) {
  return !std::holds_alternative<EnergySensor>(sensor.kind) && !readsMultipliers(sensor);
}

bool readsMultipliers(const Sensor& sensor) { return std::holds_alternative<CutReactionSensor>(sensor.kind); }

template <class Scalar>
Scalar sensorValue(const Sensor& sensor, const Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                   const VectorX<Scalar>& v, const VectorX<Scalar>& a) {
  return std::visit(
      Overloaded{
          [&](const PointSensor& s) -> Scalar {
            const auto k = static_cast<std::size_t>(s.frame);
            const auto axes = static_cast<std::size_t>(s.axes);
            const Vector3<Scalar> d = ws.rotation[k] * s.point;
            const Vector3<Scalar>& w = ws.angular_velocity[k];
            Vector3<Scalar> vector;
            if (s.quantity == Derivative::Position) vector = ws.position[k] + d - ws.position[axes];
            else if (s.quantity == Derivative::Velocity) vector = ws.velocity[k] + w.cross(d);
            else vector = ws.acceleration[k] + ws.angular_acceleration[k].cross(d) + w.cross(w.cross(d));
            return ws.rotation[axes].col(s.component).dot(vector);
          },
          [&](const JointSensor& s) -> Scalar {
            const auto i = static_cast<Eigen::Index>(s.coordinate);
            switch (s.quantity) {
              case Derivative::Position: return q[i];
              case Derivative::Velocity: return v[i];
              default: return a[i];
            }
          },
          [&](const RelativeAngleSensor& s) -> Scalar {
            // Twist of R_aᵀR_b about the axis: angle of the image of a perpendicular e in the plane (e, axis×e).
            const auto [e, f] = perpendicularPair(s.axis);
            const Matrix3<Scalar> relative =
                ws.rotation[static_cast<std::size_t>(s.frame_a)].transpose() * ws.rotation[static_cast<std::size_t>(s.frame_b)];
            const Vector3<Scalar> image = relative * e.template cast<Scalar>();
            const Scalar sine = image.dot(f.template cast<Scalar>()), cosine = image.dot(e.template cast<Scalar>());
            return atan2Of(sine, cosine);
          },
          [&](const EnergySensor&) -> Scalar { return notAStateSensor<Scalar>(sensor); },
          [&](const CutReactionSensor&) -> Scalar { return notAStateSensor<Scalar>(sensor); }},
      sensor.kind);
}

template <class Scalar>
Scalar sensorValue(const Model& model, const Sensor& sensor, const Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                   const VectorX<Scalar>& v, const VectorX<Scalar>& a, const VectorX<Scalar>& lambda) {
  const auto* reaction = std::get_if<CutReactionSensor>(&sensor.kind);
  if (!reaction) return sensorValue(sensor, ws, q, v, a);
  VectorX<Scalar> c;
  reactionCoefficients(model, ws, *reaction, c);
  return c.dot(lambda);
}

void sensorValues(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                  const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double t, SensorRow values) {
  for (std::size_t s = 0; s < model.sensors().size(); ++s) {
    const Sensor& sensor = model.sensors()[s];
    values[static_cast<Eigen::Index>(s)] =
        isStateSensor(sensor) ? sensorValue(sensor, ws, q, v, a) : systemSensorValue(model, sensor, ws, q, v, a, lambda, t);
  }
}

template double sensorValue<double>(const Sensor&, const Workspace<double>&, const VectorX<double>&,
                                    const VectorX<double>&, const VectorX<double>&);
template AdScalar sensorValue<AdScalar>(const Sensor&, const Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&, const VectorX<AdScalar>&);
template double sensorValue<double>(const Model&, const Sensor&, const Workspace<double>&, const VectorX<double>&,
                                    const VectorX<double>&, const VectorX<double>&, const VectorX<double>&);
template AdScalar sensorValue<AdScalar>(const Model&, const Sensor&, const Workspace<AdScalar>&,
                                        const VectorX<AdScalar>&, const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&);

}  // namespace mbsopt
