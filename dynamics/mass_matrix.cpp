#include "dynamics/mass_matrix.hpp"

#include "dynamics/kinematics.hpp"

namespace mbsopt {

namespace {

/// World-axes centre of mass and inertia of each body at the rotations in ws, shared by all columns.
struct BodyInertia {
  std::vector<Eigen::Vector3d> centre;
  std::vector<Eigen::Matrix3d> inertia;

  void update(const Model& model, const Workspace<double>& ws) {
    centre.resize(model.bodies().size());
    inertia.resize(model.bodies().size());
    for (std::size_t b = 0; b < model.bodies().size(); ++b) {
      const Body& body = model.bodies()[b];
      const Eigen::Matrix3d& R = ws.rotation[static_cast<std::size_t>(body.frame)];
      centre[b] = R * body.centre_of_mass;
      inertia[b] = R * body.inertia * R.transpose();
    }
  }
};

/// Inertia wrenches of the bodies at the frame accelerations in ws, then the backward recursion
/// (22)-(23) and the residual rows (24): the generalised forces of every coordinate.
void inertiaForces(const Model& model, Workspace<double>& ws, const BodyInertia& bodies, Eigen::VectorXd& forces) {
  for (std::size_t k = 0; k < ws.force.size(); ++k) {
    ws.force[k].setZero();
    ws.moment[k].setZero();
  }
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    const Body& body = model.bodies()[b];
    const auto k = static_cast<std::size_t>(body.frame);
    const Eigen::Vector3d& c = bodies.centre[b];
    const Eigen::Vector3d& alpha = ws.angular_acceleration[k];
    const Eigen::Vector3d force = body.mass * (ws.acceleration[k] + alpha.cross(c));
    ws.force[k] += force;
    ws.moment[k] += bodies.inertia[b] * alpha + c.cross(force);
  }
  const auto& elements = model.elements();
  for (std::size_t k = elements.size(); k-- > 0;) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry), s = static_cast<std::size_t>(element.exit);
    if (element.coordinate >= 0)
      forces[element.coordinate] = ws.motion_linear[k].dot(ws.force[s]) + ws.motion_angular[k].dot(ws.moment[s]);
    ws.force[e] += ws.force[s];
    ws.moment[e] += ws.moment[s] + (ws.position[s] - ws.position[e]).cross(ws.force[s]);
  }
}

}  // namespace

void massMatrix(const Model& model, Workspace<double>& ws, const std::vector<int>& coordinates, Eigen::MatrixXd& M) {
  const auto n = static_cast<Eigen::Index>(coordinates.size());
  M.resize(n, n);
  thread_local BodyInertia bodies;
  thread_local Eigen::VectorXd column;
  bodies.update(model, ws);
  column.resize(model.coordinateCount());
  for (Eigen::Index c = 0; c < n; ++c) {
    // Frame accelerations caused by q̈_j = 1 alone.
    unitRatePass(model, ws, coordinates[static_cast<std::size_t>(c)], ws.angular_acceleration, ws.acceleration);
    inertiaForces(model, ws, bodies, column);
    for (Eigen::Index r = 0; r < n; ++r) M(r, c) = column[coordinates[static_cast<std::size_t>(r)]];
  }
}

void massMatrix(const Model& model, Workspace<double>& ws, Eigen::MatrixXd& M) {
  massMatrix(model, ws, allCoordinates(model), M);
}

}  // namespace mbsopt
