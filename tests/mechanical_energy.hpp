// Mechanical energy of a state from the frame kinematics alone (not from the mass matrix), so that
// energy tests check the integrator and the recursions independently.
#pragma once

#include <Eigen/Core>

#include "mbsopt/algorithms/kinematics.hpp"

namespace mbsopt::test {

struct Energy {
  double kinetic = 0.0;
  double potential = 0.0;
  double total() const { return kinetic + potential; }
};

/// T = Σ ½ m |v_c|² + ½ ωᵀ I ω and V = −Σ m g·r_c from the frame kinematics of the state.
inline Energy mechanicalEnergy(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                               const Eigen::VectorXd& v) {
  forwardKinematics(model, ws, q, v, Eigen::VectorXd::Zero(q.size()).eval(), KinematicsLevel::Velocity);
  Energy energy;
  for (const Body& body : model.bodies()) {
    const auto k = static_cast<std::size_t>(body.frame);
    const Eigen::Matrix3d& R = ws.rotation[k];
    const Eigen::Vector3d& w = ws.angular_velocity[k];
    const Eigen::Vector3d c = R * model.centreOfMass(body);
    const Eigen::Vector3d v_c = ws.velocity[k] + w.cross(c);
    const double mass = model.value(body.mass);
    energy.kinetic += 0.5 * mass * v_c.squaredNorm() + 0.5 * w.dot(R * model.inertia(body) * R.transpose() * w);
    energy.potential -= mass * model.gravity().dot(ws.position[k] + c);
  }
  return energy;
}

}  // namespace mbsopt::test
