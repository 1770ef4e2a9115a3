#include "dynamics/mass_matrix.hpp"

#include <vector>

namespace mbsopt {

void massMatrix(const Model& model, Workspace<double>& ws, Eigen::MatrixXd& M) {
  const Eigen::Index n = model.coordinateCount();
  M.resize(n, n);
  const auto& elements = model.elements();
  // World-axes centre of mass and inertia of each body, shared by all columns.
  thread_local std::vector<Eigen::Vector3d> centre;
  thread_local std::vector<Eigen::Matrix3d> inertia;
  centre.resize(model.bodies().size());
  inertia.resize(model.bodies().size());
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    const Body& body = model.bodies()[b];
    const Eigen::Matrix3d& R = ws.rotation[static_cast<std::size_t>(body.frame)];
    centre[b] = R * body.centre_of_mass;
    inertia[b] = R * body.inertia * R.transpose();
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    // Forward: frame accelerations caused by q̈_j = 1 alone.
    for (std::size_t k = 0; k < elements.size(); ++k) {
      const KinematicElement& element = elements[k];
      const auto e = static_cast<std::size_t>(element.entry), s = static_cast<std::size_t>(element.exit);
      const double unit = element.coordinate == j ? 1.0 : 0.0;
      const Eigen::Vector3d r = ws.position[s] - ws.position[e];
      ws.angular_acceleration[s] = ws.angular_acceleration[e] + ws.motion_angular[k] * unit;
      ws.acceleration[s] = ws.acceleration[e] + ws.angular_acceleration[e].cross(r) + ws.motion_linear[k] * unit;
    }
    for (std::size_t k = 0; k < ws.force.size(); ++k) {
      ws.force[k].setZero();
      ws.moment[k].setZero();
    }
    for (std::size_t b = 0; b < model.bodies().size(); ++b) {
      const Body& body = model.bodies()[b];
      const auto k = static_cast<std::size_t>(body.frame);
      const Eigen::Vector3d& c = centre[b];
      const Eigen::Vector3d& alpha = ws.angular_acceleration[k];
      const Eigen::Vector3d force = body.mass * (ws.acceleration[k] + alpha.cross(c));
      ws.force[k] += force;
      ws.moment[k] += inertia[b] * alpha + c.cross(force);
    }
    // Backward (22)-(23) and the residual rows (24).
    for (std::size_t k = elements.size(); k-- > 0;) {
      const KinematicElement& element = elements[k];
      const auto e = static_cast<std::size_t>(element.entry), s = static_cast<std::size_t>(element.exit);
      if (element.coordinate >= 0)
        M(element.coordinate, j) = ws.motion_linear[k].dot(ws.force[s]) + ws.motion_angular[k].dot(ws.moment[s]);
      ws.force[e] += ws.force[s];
      ws.moment[e] += ws.moment[s] + (ws.position[s] - ws.position[e]).cross(ws.force[s]);
    }
  }
}

}  // namespace mbsopt
