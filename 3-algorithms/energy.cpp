#include "mbsopt/algorithms/energy.hpp"

#include <cmath>

#include "mbsopt/model/overloaded.hpp"
#include "mbsopt/algorithms/kinematics.hpp"

namespace mbsopt {

namespace {

/// Length of a point spring-damper: the distance between its two points.
double springLength(const PointSpringDamper& s, const Workspace<double>& ws) {
  const auto a = static_cast<std::size_t>(s.frame_a), b = static_cast<std::size_t>(s.frame_b);
  return ((ws.position[b] + ws.rotation[b] * s.point_b) - (ws.position[a] + ws.rotation[a] * s.point_a)).norm();
}

/// Δ = heading(frame) − ψ(s) of a track guidance, wrapped to (−π, π], as in its force (residual.cpp).
double guidanceDeviation(const Model& model, const TrackGuidance& g, const Workspace<double>& ws,
                         const Eigen::VectorXd& q) {
  const KinematicElement& slider =
      model.elements()[static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(g.slider_coordinate)].element)];
  const Track& track = model.track(std::get<CurveSliderJoint>(slider.kind).track);
  const double heading = track.at(q[g.slider_coordinate]).heading;
  const Eigen::Vector3d x =
      ws.rotation[static_cast<std::size_t>(slider.entry)].transpose() * ws.rotation[static_cast<std::size_t>(g.frame)].col(0);
  const double c = std::cos(heading), s = std::sin(heading);
  return std::atan2(c * x.y() - s * x.x(), c * x.x() + s * x.y());
}

}  // namespace

MechanicalEnergy mechanicalEnergyOfFrames(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v, double t) {
  MechanicalEnergy energy;
  for (const JointArmature& armature : model.armatures())
    energy.kinetic += 0.5 * model.value(armature.inertia) * v[armature.coordinate] * v[armature.coordinate];
  for (const Body& body : model.bodies()) {
    const auto k = static_cast<std::size_t>(body.frame);
    const Eigen::Matrix3d& R = ws.rotation[k];
    const Eigen::Vector3d& w = ws.angular_velocity[k];
    const Eigen::Vector3d c = R * model.centreOfMass(body);
    const Eigen::Vector3d w_body = R.transpose() * w;  // ωᵀ(R I Rᵀ)ω in body axes
    const double mass = model.value(body.mass);
    energy.kinetic += 0.5 * mass * (ws.velocity[k] + w.cross(c)).squaredNorm() +
                      0.5 * w_body.dot(model.inertia(body) * w_body);
    energy.gravity -= mass * model.gravity().dot(ws.position[k] + c);
  }
  for (const ForceElement& force : model.forces()) {
    energy.springs += std::visit(
        Overloaded{[&](const JointSpringDamper& s) {
                     const double stretch = q[s.coordinate] - model.value(s.rest, t);
                     return 0.5 * model.value(s.stiffness) * stretch * stretch;
                   },
                   [&](const PointSpringDamper& s) {
                     const double stretch = springLength(s, ws) - model.value(s.rest_length);
                     return 0.5 * model.value(s.stiffness) * stretch * stretch;
                   },
                   [&](const JointActuation&) { return 0.0; },  // work of an external force, no potential
                   [&](const RotationalDamper&) { return 0.0; },  // dissipation only
                   [&](const TrackGuidance& g) {
                     const double deviation = guidanceDeviation(model, g, ws, q);
                     return 0.5 * model.value(g.stiffness) * deviation * deviation;
                   }},
        force);
  }
  return energy;
}

MechanicalEnergy mechanicalEnergy(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& v, double t) {
  forwardKinematics(model, ws, q, v, v, KinematicsLevel::Velocity);  // the accelerations (here v) are not read
  return mechanicalEnergyOfFrames(model, ws, q, v, t);
}

double energyPart(const MechanicalEnergy& energy, EnergyPart part) {
  switch (part) {
    case EnergyPart::Kinetic: return energy.kinetic;
    case EnergyPart::Potential: return energy.potential();
    default: return energy.total();
  }
}

}  // namespace mbsopt
