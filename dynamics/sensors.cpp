#include "dynamics/sensors.hpp"

#include <cmath>

#include "dynamics/overloaded.hpp"

namespace mbsopt {

template <class Scalar>
Scalar sensorValue(const Sensor& sensor, const Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                   const VectorX<Scalar>& v, const VectorX<Scalar>& a) {
  return std::visit(
      Overloaded{
          [&](const PointSensor& s) -> Scalar {
            const auto k = static_cast<std::size_t>(s.frame);
            const auto axes = static_cast<std::size_t>(s.axes);
            const Vector3<Scalar> d = ws.rotation[k] * s.point.template cast<Scalar>();
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
            using std::atan2;
            const auto [e, f] = perpendicularPair(s.axis);
            const Matrix3<Scalar> relative =
                ws.rotation[static_cast<std::size_t>(s.frame_a)].transpose() * ws.rotation[static_cast<std::size_t>(s.frame_b)];
            const Vector3<Scalar> image = relative * e.template cast<Scalar>();
            return atan2(image.dot(f.template cast<Scalar>()), image.dot(e.template cast<Scalar>()));
          }},
      sensor.kind);
}

Eigen::MatrixXd sensorHistory(const Model& model, const Trajectory& trajectory) {
  Workspace<double> ws(model);
  const Eigen::Index points = trajectory.time.size();
  Eigen::MatrixXd out(points, static_cast<Eigen::Index>(model.sensors().size()));
  Eigen::VectorXd q, v, a;
  for (Eigen::Index k = 0; k < points; ++k) {
    q = trajectory.q.col(k);
    v = trajectory.v.col(k);
    a = trajectory.a.col(k);
    forwardKinematics(model, ws, q, v, a, KinematicsLevel::Acceleration);
    for (std::size_t s = 0; s < model.sensors().size(); ++s)
      out(k, static_cast<Eigen::Index>(s)) = sensorValue(model.sensors()[s], ws, q, v, a);
  }
  return out;
}

template double sensorValue<double>(const Sensor&, const Workspace<double>&, const VectorX<double>&,
                                    const VectorX<double>&, const VectorX<double>&);
template AdScalar sensorValue<AdScalar>(const Sensor&, const Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&, const VectorX<AdScalar>&);

}  // namespace mbsopt
