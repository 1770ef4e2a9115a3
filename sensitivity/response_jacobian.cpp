#include "sensitivity/response_jacobian.hpp"

#include <algorithm>

#include "dynamics/kinematics.hpp"
#include "dynamics/sensors.hpp"

namespace mbsopt {

ResponseJacobian responseJacobian(const Model& model, Workspace<AdScalar>& ws, const Sensor& sensor,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
  const Eigen::Index n = model.coordinateCount();
  ResponseJacobian out;
  out.position.resize(n);
  out.velocity.resize(n);
  out.acceleration.resize(n);
  // Inputs ordered (q, q̇, q̈); passes of at most kMaxAdDirections seeded directions each.
  for (Eigen::Index first = 0; first < 3 * n; first += kMaxAdDirections) {
    const Eigen::Index count = std::min<Eigen::Index>(kMaxAdDirections, 3 * n - first);
    const VectorX<AdScalar> q_ad = seededVector(q, 0, first, count);
    const VectorX<AdScalar> v_ad = seededVector(v, n, first, count);
    const VectorX<AdScalar> a_ad = seededVector(a, 2 * n, first, count);
    forwardKinematics(model, ws, q_ad, v_ad, a_ad, KinematicsLevel::Acceleration);
    const AdScalar g = sensorValue(sensor, ws, q_ad, v_ad, a_ad);
    out.value = g.value();
    for (Eigen::Index j = 0; j < count; ++j) {
      const Eigen::Index input = first + j;
      if (input < n) out.position[input] = g.derivatives()[j];
      else if (input < 2 * n) out.velocity[input - n] = g.derivatives()[j];
      else out.acceleration[input - 2 * n] = g.derivatives()[j];
    }
  }
  return out;
}

}  // namespace mbsopt
