#include "mbsopt/algorithms/residual.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "mbsopt/model/overloaded.hpp"
#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/planar_recursions.hpp"

namespace mbsopt {

namespace {

/// Whether the frames in the workspace move: at rest every frame velocity is zero, and the terms in
/// them are skipped (exact zeros there).
enum class FrameMotion { Moving, AtRest };

/// Each body's centre of mass and inertia tensor in ground axes, once per geometry (see Workspace).
template <class Scalar>
void updateBodyAxes(const Model& model, Workspace<Scalar>& ws) {
  if (ws.body_axes_current) return;
  const auto& bodies = model.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const Matrix3<Scalar>& R = ws.rotation[static_cast<std::size_t>(body.frame)];
    const Vector3<Scalar> c = parameter(model, ws, body.centre_of_mass);
    if (model.planar()) {  // R turns about z: its xy block acts on (c_x, c_y), c_z stays; the planar
                           // wrenches read I_zz alone, the same in every axes about z
      ws.body_centre[i] = Vector3<Scalar>(R(0, 0) * c.x() + R(0, 1) * c.y(), R(1, 0) * c.x() + R(1, 1) * c.y(), c.z());
      continue;
    }
    ws.body_centre[i] = R * c;
    Matrix3<Scalar> body_inertia = model.inertia(body).template cast<Scalar>();
    body_inertia.diagonal() = parameter(model, ws, body.moments_of_inertia);
    ws.body_inertia[i] = R * body_inertia * R.transpose();
  }
  ws.body_axes_current = true;
}

/// Inertia and gravity g of each body as a required wrench on its frame (the ΔE, ΔM of (22)-(23)).
template <class Scalar>
void addBodyWrenches(const Model& model, Workspace<Scalar>& ws, const Vector3<Scalar>& g, FrameMotion motion) {
  const auto& bodies = model.bodies();
  updateBodyAxes(model, ws);
  if (model.planar()) return planarBodyWrenches(model, ws, g, motion == FrameMotion::Moving);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const auto k = static_cast<std::size_t>(body.frame);
    const Vector3<Scalar>& alpha = ws.angular_acceleration[k];
    const Vector3<Scalar>& c = ws.body_centre[i];
    const Matrix3<Scalar>& inertia = ws.body_inertia[i];
    const Scalar mass = parameter(model, ws, body.mass);
    if (motion == FrameMotion::AtRest) {
      const Vector3<Scalar> force = mass * ((ws.acceleration[k] + alpha.cross(c)) - g);
      ws.force[k] += force;
      ws.moment[k] += inertia * alpha + c.cross(force);
      continue;
    }
    const Vector3<Scalar>& w = ws.angular_velocity[k];
    const Vector3<Scalar> a_c = ws.acceleration[k] + alpha.cross(c) + w.cross(w.cross(c));
    const Vector3<Scalar> force = mass * (a_c - g);
    ws.force[k] += force;
    ws.moment[k] += inertia * alpha + w.cross(inertia * w) + c.cross(force);
  }
}

/// Point-to-point spring-dampers act as applied (so subtracted) forces on their two frames, with the
/// stiffness and damping given (the element's parameters, or 1 and 0 for the derivative in one).
template <class Scalar>
void addPointSpringWrenches(const Model& model, const PointSpringDamper& s, Workspace<Scalar>& ws,
                            const Scalar& stiffness, const Scalar& damping) {
  using std::sqrt;
  const auto a = static_cast<std::size_t>(s.frame_a), b = static_cast<std::size_t>(s.frame_b);
  const Vector3<Scalar> ra = ws.rotation[a] * s.point_a;
  const Vector3<Scalar> rb = ws.rotation[b] * s.point_b;
  const Vector3<Scalar> d = (ws.position[b] + rb) - (ws.position[a] + ra);
  const Vector3<Scalar> d_rate =
      (ws.velocity[b] + ws.angular_velocity[b].cross(rb)) - (ws.velocity[a] + ws.angular_velocity[a].cross(ra));
  const Scalar length = sqrt(d.squaredNorm());
  if (!(valueOf(length) > 1e-12 * (1.0 + std::abs(model.value(s.rest_length)))))
    throw DegenerateElementError(s.name, "point spring-damper '" + s.name + "': its two points coincide, so its direction is undefined");
  const Vector3<Scalar> u = d / length;
  const Scalar tension = stiffness * (length - parameter(model, ws, s.rest_length)) + damping * u.dot(d_rate);
  const Vector3<Scalar> on_a = tension * u;  // pulls a towards b when stretched
  addForce(model, ws, a, Vector3<Scalar>(-on_a));
  addMoment(model, ws, a, Vector3<Scalar>(-ra.cross(on_a)));
  addForce(model, ws, b, on_a);
  addMoment(model, ws, b, Vector3<Scalar>(rb.cross(on_a)));
}

/// A rotational damper's torque −c (ω_b − ω_a) on frame b and its opposite on frame a, as applied
/// (so subtracted) moments, with the damping given (as for the point spring-dampers).
template <class Scalar>
void addRotationalDamperWrenches(const Model& model, const RotationalDamper& d, Workspace<Scalar>& ws, const Scalar& damping) {
  const auto a = static_cast<std::size_t>(d.frame_a), b = static_cast<std::size_t>(d.frame_b);
  const Vector3<Scalar> on_b = -damping * (ws.angular_velocity[b] - ws.angular_velocity[a]);
  addMoment(model, ws, b, Vector3<Scalar>(-on_b));
  addMoment(model, ws, a, on_b);
}

/// Track guidance torque on its frame, reaction on the track's frame, and −κτ on the slider
/// coordinate, with the stiffness and damping given (as for the point spring-dampers).
template <class Scalar>
void addTrackGuidance(const Model& model, const TrackGuidance& g, Workspace<Scalar>& ws, const VectorX<Scalar>& v,
                      VectorX<Scalar>& f, const Scalar& stiffness, const Scalar& damping) {
  const auto element = static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(g.slider_coordinate)].element);
  const KinematicElement& slider = model.elements()[element];
  const auto base = static_cast<std::size_t>(slider.entry), frame = static_cast<std::size_t>(g.frame);
  const auto i = static_cast<Eigen::Index>(g.slider_coordinate);
  const SliderTrack<Scalar>& track = ws.slider_track[element];  // ψ(s) and κ(s) of the geometry stage
  const Scalar& c = track.cos_heading;
  const Scalar& s = track.sin_heading;
  const Scalar& curvature = track.curvature;
  const Matrix3<Scalar>& Rb = ws.rotation[base];
  const Matrix3<Scalar>& Rf = ws.rotation[frame];
  const bool planar = model.planar();  // both frames turn about z: the xy blocks alone, the binormal is z
  // The frame's heading in base axes (x, y), and its rotation rate relative to the base about the binormal.
  Scalar x, y, relative_rate;
  if (planar) {
    x = Rb(0, 0) * Rf(0, 0) + Rb(1, 0) * Rf(1, 0);
    y = Rb(0, 1) * Rf(0, 0) + Rb(1, 1) * Rf(1, 0);
    relative_rate = ws.angular_velocity[frame].z() - ws.angular_velocity[base].z();
  } else {
    const Vector3<Scalar> heading = Rb.transpose() * Rf.col(0);
    x = heading.x();
    y = heading.y();
    relative_rate = (ws.angular_velocity[frame] - ws.angular_velocity[base]).dot(Rb.col(2));
  }
  const Scalar deviation = atan2Of(Scalar(c * y - s * x), Scalar(c * x + s * y));  // Δ, wrapped to (−π, π]
  const Scalar deviation_rate = relative_rate - curvature * v[i];
  const Scalar torque = -stiffness * deviation - damping * deviation_rate;
  if (planar) {
    ws.moment[frame].z() -= torque;
    ws.moment[base].z() += torque;
  } else {
    const Vector3<Scalar> binormal = Rb.col(2);
    ws.moment[frame] -= torque * binormal;  // applied on the frame
    ws.moment[base] += torque * binormal;   // reaction on the track
  }
  f[i] += curvature * torque;  // generalised force −κτ on s, moved to the residual side
}

/// Every frame's force and moment set to zero: on a planar model the components written there,
/// F_x, F_y and M_z (addForce, addMoment).
template <class Scalar>
void clearWrenches(const Model& model, Workspace<Scalar>& ws) {
  if (model.planar()) {
    for (std::size_t k = 0; k < ws.force.size(); ++k) {
      setZero(ws.force[k].x());
      setZero(ws.force[k].y());
      setZero(ws.moment[k].z());
    }
    return;
  }
  for (std::size_t k = 0; k < ws.force.size(); ++k) {
    ws.force[k].setZero();
    ws.moment[k].setZero();
  }
}

/// The body wrenches with gravity g at the kinematics in ws, every other wrench cleared.
template <class Scalar>
void startWrenches(const Model& model, Workspace<Scalar>& ws, const Vector3<Scalar>& g, FrameMotion motion) {
  clearWrenches(model, ws);
  addBodyWrenches(model, ws, g, motion);
}

/// Backward recursion (22)-(23) and the residual of each active element (24), added to f.
template <class Scalar>
void addElementResiduals(const Model& model, Workspace<Scalar>& ws, VectorX<Scalar>& f) {
  const auto& elements = model.elements();
  if (model.planar()) return planarElementResiduals(model, ws, f);
  for (std::size_t k = elements.size(); k-- > 0;) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    if (element.coordinate >= 0)
      f[element.coordinate] += ws.motion_linear[k].dot(ws.force[s]) + ws.motion_angular[k].dot(ws.moment[s]);
    ws.force[e] += ws.force[s];
    ws.moment[e] += ws.moment[s] + (ws.position[s] - ws.position[e]).cross(ws.force[s]);
  }
}

/// The rotor inertias' J q̈ on their coordinates (JointArmature), added to f.
template <class Scalar>
void addArmatureForces(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a, VectorX<Scalar>& f) {
  for (const JointArmature& armature : model.armatures()) {
    const auto i = static_cast<Eigen::Index>(armature.coordinate);
    f[i] += parameter(model, ws, armature.inertia) * a[i];
  }
}

}  // namespace

template <class Scalar>
void residual(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, const VectorX<Scalar>& v,
              const VectorX<Scalar>& a, const VectorX<Scalar>& lambda, double t, VectorX<Scalar>& f) {
  const Eigen::Index n = model.coordinateCount();
  if (q.size() != n || v.size() != n || a.size() != n || (lambda.size() != 0 && lambda.size() != model.constraintCount()))
    throw std::invalid_argument("residual: q, q̇, q̈ need " + std::to_string(n) + " entries and λ 0 or " +
                                std::to_string(model.constraintCount()));
  forwardKinematics(model, ws, q, v, a, KinematicsLevel::Acceleration);
  residualFromKinematics(model, ws, q, v, a, lambda, t, f);
}

template <class Scalar>
void residualFromKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                            const VectorX<Scalar>& v, const VectorX<Scalar>& a, const VectorX<Scalar>& lambda,
                            double t, VectorX<Scalar>& f) {
  startWrenches(model, ws, parameter(model, ws, model.gravityParameters()), FrameMotion::Moving);
  f.setZero(model.coordinateCount());
  for (const ForceElement& element : model.forces()) {
    std::visit(Overloaded{[&](const JointSpringDamper& s) {
                            const auto i = static_cast<Eigen::Index>(s.coordinate);
                            f[i] += parameter(model, ws, s.stiffness) * (q[i] - timeValue(model, ws, s.rest, t)) +
                                    parameter(model, ws, s.damping) * (v[i] - timeValue(model, ws, s.rest, t, 1));
                          },
                          [&](const PointSpringDamper& s) {
                            addPointSpringWrenches(model, s, ws, parameter(model, ws, s.stiffness),
                                                   parameter(model, ws, s.damping));
                          },
                          [&](const JointActuation& s) {
                            f[static_cast<Eigen::Index>(s.coordinate)] -= timeValue(model, ws, s.force, t);
                          },
                          [&](const TrackGuidance& g) {
                            addTrackGuidance(model, g, ws, v, f, parameter(model, ws, g.stiffness),
                                             parameter(model, ws, g.damping));
                          },
                          [&](const RotationalDamper& d) {
                            addRotationalDamperWrenches(model, d, ws, parameter(model, ws, d.damping));
                          }},
               element);
  }
  if (model.constraintCount() > 0 && lambda.size() > 0) addConstraintWrenches(model, ws, lambda);
  addElementResiduals(model, ws, f);
  addArmatureForces(model, ws, a, f);
}

template <class Scalar>
void inertialAndLoopForcesFromKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a,
                                         const VectorX<Scalar>& lambda, VectorX<Scalar>& f) {
  if (lambda.size() != model.constraintCount())
    throw std::invalid_argument("inertialAndLoopForces: λ needs " + std::to_string(model.constraintCount()) + " entries");
  startWrenches(model, ws, Vector3<Scalar>(Vector3<Scalar>::Zero()), FrameMotion::AtRest);
  f.setZero(model.coordinateCount());
  if (model.constraintCount() > 0) addConstraintWrenches(model, ws, lambda);
  addElementResiduals(model, ws, f);
  addArmatureForces(model, ws, a, f);
}

namespace {

/// Calls apply(from's entry, to's entry) on every entry of the geometry stage's results that
/// constantGeometry makes constants of an AD pass (see there), from and to alike shaped.
template <class From, class Apply>
void forEachGeometryEntry(const Model& model, From& from, Workspace<AdScalar>& to, Apply apply) {
  const auto each = [&apply](auto& x, auto& y) {
    for (Eigen::Index i = 0; i < x.size(); ++i) apply(x(i), y(i));
  };
  const auto track = [&apply](auto& x, SliderTrack<AdScalar>& y) {
    apply(x.cos_heading, y.cos_heading);
    apply(x.sin_heading, y.sin_heading);
    apply(x.curvature, y.curvature);
  };
  if (model.planar()) {
    for (std::size_t k = 0; k < from.rotation.size(); ++k) {
      for (const auto& [i, j] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}})
        apply(from.rotation[k](i, j), to.rotation[k](i, j));
      each(from.position[k], to.position[k]);
    }
    for (std::size_t k = 0; k < from.motion_angular.size(); ++k) {
      apply(from.motion_angular[k].z(), to.motion_angular[k].z());
      apply(from.bias_angular[k].z(), to.bias_angular[k].z());
      for (int i = 0; i < 2; ++i) {
        apply(from.motion_linear[k][i], to.motion_linear[k][i]);
        apply(from.bias_linear[k][i], to.bias_linear[k][i]);
      }
    }
    for (std::size_t k = 0; k < from.body_centre.size(); ++k) each(from.body_centre[k], to.body_centre[k]);
    for (std::size_t k = 0; k < from.slider_track.size(); ++k) track(from.slider_track[k], to.slider_track[k]);
    return;
  }
  for (std::size_t k = 0; k < from.rotation.size(); ++k) each(from.rotation[k], to.rotation[k]);
  for (std::size_t k = 0; k < from.position.size(); ++k) each(from.position[k], to.position[k]);
  for (std::size_t k = 0; k < from.motion_angular.size(); ++k) {
    each(from.motion_angular[k], to.motion_angular[k]);
    each(from.motion_linear[k], to.motion_linear[k]);
    each(from.bias_angular[k], to.bias_angular[k]);
    each(from.bias_linear[k], to.bias_linear[k]);
  }
  for (std::size_t k = 0; k < from.body_centre.size(); ++k) {
    each(from.body_centre[k], to.body_centre[k]);
    each(from.body_inertia[k], to.body_inertia[k]);
  }
  for (std::size_t k = 0; k < from.slider_track.size(); ++k) track(from.slider_track[k], to.slider_track[k]);
  for (std::size_t k = 0; k < from.ball_chart.size(); ++k) {
    each(from.ball_chart[k].rotation_vector, to.ball_chart[k].rotation_vector);
    apply(from.ball_chart[k].beta, to.ball_chart[k].beta);
    apply(from.ball_chart[k].alpha_rate, to.ball_chart[k].alpha_rate);
    apply(from.ball_chart[k].beta_rate, to.ball_chart[k].beta_rate);
  }
}

}  // namespace

void constantGeometry(const Model& model, Workspace<double>& from, Workspace<AdScalar>& to) {
  updateBodyAxes(model, from);
  forEachGeometryEntry(model, from, to, [](double x, AdScalar& y) {
    y.value() = x;
    y.derivatives().setZero();
  });
  to.body_axes_current = true;
}

void dropGeometryDerivatives(const Model& model, Workspace<AdScalar>& ws) {
  updateBodyAxes(model, ws);
  forEachGeometryEntry(model, ws, ws, [](AdScalar&, AdScalar& y) { y.derivatives().setZero(); });
}

namespace {

/// The force element whose stiffness or damping p is (f is linear in p through it alone), or null.
const ForceElement* linearForceOwner(const Model& model, ParameterIndex p) {
  for (const ForceElement& element : model.forces()) {
    const bool owned = std::visit(Overloaded{[](const JointActuation&) { return false; },
                                             [p](const RotationalDamper& d) { return p == d.damping; },
                                             [p](const auto& e) { return p == e.stiffness || p == e.damping; }},
                                  element);
    if (owned) return &element;
  }
  return nullptr;
}

}  // namespace

bool isLinearForceParameter(const Model& model, ParameterIndex p) { return linearForceOwner(model, p) != nullptr; }

bool linearForceParameterReadsKinematics(const Model& model, ParameterIndex p) {
  const ForceElement* owner = linearForceOwner(model, p);
  return owner && !std::holds_alternative<JointSpringDamper>(*owner);
}

bool linearForceParameterColumn(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v, double t, ParameterIndex p, Eigen::VectorXd& column) {
  const ForceElement* owner = linearForceOwner(model, p);
  if (!owner) return false;
  column.setZero(model.coordinateCount());
  if (const auto* spring = std::get_if<JointSpringDamper>(owner)) {  // a force on its own coordinate only
    const auto i = static_cast<Eigen::Index>(spring->coordinate);
    column[i] = p == spring->stiffness ? q[i] - model.value(spring->rest, t) : v[i] - model.value(spring->rest, t, 1);
    return true;
  }
  // The element's force is k·(a stiffness term) + c·(a damping term): ∂f/∂k is its force with k = 1,
  // c = 0, carried to the coordinates by the same backward recursion (22)-(24).
  clearWrenches(model, ws);
  std::visit(Overloaded{[](const JointSpringDamper&) {},
                        [&](const PointSpringDamper& s) {
                          addPointSpringWrenches(model, s, ws, p == s.stiffness ? 1.0 : 0.0, p == s.damping ? 1.0 : 0.0);
                        },
                        [&](const TrackGuidance& g) {
                          addTrackGuidance(model, g, ws, v, column, p == g.stiffness ? 1.0 : 0.0,
                                           p == g.damping ? 1.0 : 0.0);
                        },
                        [&](const RotationalDamper& d) { addRotationalDamperWrenches(model, d, ws, 1.0); },
                        [](const JointActuation&) {}},
             *owner);
  addElementResiduals(model, ws, column);  // the unit force's wrenches, to the coordinates
  return true;
}

template void residual<double>(const Model&, Workspace<double>&, const VectorX<double>&, const VectorX<double>&,
                               const VectorX<double>&, const VectorX<double>&, double, VectorX<double>&);
template void residual<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                 const VectorX<AdScalar>&, const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                 double, VectorX<AdScalar>&);
template void residualFromKinematics<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                               const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                               const VectorX<AdScalar>&, double, VectorX<AdScalar>&);
template void inertialAndLoopForcesFromKinematics<AdScalar>(const Model&, Workspace<AdScalar>&,
                                                            const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                                            VectorX<AdScalar>&);

}  // namespace mbsopt
