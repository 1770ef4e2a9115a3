#include "dynamics/kinematics.hpp"
#include "dynamics/overloaded.hpp"

#include <cmath>

namespace mbsopt {

namespace {

/// Motion of the exit frame relative to the entry frame, already turned into ground axes by the
/// entry rotation R_e. Terms an element does not have stay zero and cost no product.
template <class Scalar>
struct RelativeMotion {
  Matrix3<Scalar> rotation;                                ///< absolute rotation of the exit frame, R_e R_rel
  Vector3<Scalar> translation = Vector3<Scalar>::Zero();   ///< r_s/e
  Vector3<Scalar> angular_axis = Vector3<Scalar>::Zero();  ///< ∂ω_rel/∂q̇
  Vector3<Scalar> linear_axis = Vector3<Scalar>::Zero();   ///< ∂v_rel/∂q̇
  Vector3<Scalar> angular_bias = Vector3<Scalar>::Zero();  ///< (α_rel − angular_axis·q̈)/q̇²
  Vector3<Scalar> linear_bias = Vector3<Scalar>::Zero();   ///< (a_rel − linear_axis·q̈)/q̇²
  SliderTrack<Scalar> track;                               ///< a curve slider's track at s
};

template <class Scalar>
RelativeMotion<Scalar> relativeMotion(const ElementKind& kind, const Matrix3<Scalar>& Re, const Scalar& q,
                                      bool rates) {
  RelativeMotion<Scalar> m;
  std::visit(Overloaded{
                 [&](const Offset& e) {
                   m.rotation = e.rotates ? Matrix3<Scalar>(Re * e.rotation) : Re;
                   m.translation = Re * e.translation;
                 },
                 [&](const RevoluteJoint& e) {
                   m.rotation = turnedAbout(Re, e.axis, q);
                   m.angular_axis = Re * e.axis;
                 },
                 [&](const PrismaticJoint& e) {
                   m.rotation = Re;
                   m.translation = Re * (e.axis * q);
                   m.linear_axis = Re * e.axis;
                 },
                 [&](const CurveSliderJoint& e) {
                   // dr/ds = t to first order, as the heading and curvature (trackStateAt).
                   using std::cos;
                   using std::sin;
                   const TrackState<Scalar> track = trackStateAt(*e.track, q);
                   const TrackPoint& point = track.point;
                   const Scalar& ds = track.offset;
                   const Scalar& heading = track.heading;
                   const Scalar& curvature = track.curvature;
                   const Scalar cos_heading = cos(heading), sin_heading = sin(heading);
                   m.track = {cos_heading, sin_heading, curvature};
                   const Vector3<Scalar> tangent(cos_heading, sin_heading, Scalar(0));
                   const Eigen::Vector3d tangent_at_s(valueOf(cos_heading), valueOf(sin_heading), 0.0);  // t(s)
                   m.translation = Re * (point.position + tangent_at_s * ds);
                   m.linear_axis = Re * tangent;
                   if (rates) {  // a = t s̈ + κ ṡ² n
                     const Vector3<Scalar> normal(-sin_heading, cos_heading, Scalar(0));
                     m.linear_bias = Re * (curvature * normal);
                   }
                   if (e.orientation == SliderOrientation::Translate) {
                     m.rotation = Re;
                     return;
                   }
                   m.rotation = turnedAbout(Re, Eigen::Vector3d::UnitZ(), cos_heading, sin_heading);
                   m.angular_axis = Re * Vector3<Scalar>(Scalar(0), Scalar(0), curvature);
                   if (rates)  // α = (κ s̈ + κ' ṡ²) z
                     m.angular_bias = Re * Vector3<Scalar>(Scalar(0), Scalar(0), Scalar(point.curvature_derivative));
                 }},
             kind);
  return m;
}

template <class Scalar>
void geometry(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, bool axes) {
  ws.body_axes_current = false;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Scalar qi = element.coordinate >= 0 ? q[element.coordinate] : Scalar(0);
    const RelativeMotion<Scalar> rel = relativeMotion(element.kind, ws.rotation[e], qi, axes);
    ws.rotation[s] = rel.rotation;
    ws.position[s] = ws.position[e] + rel.translation;
    if (std::holds_alternative<CurveSliderJoint>(element.kind)) ws.slider_track[k] = rel.track;
    // An element without a coordinate (an offset) keeps the zero axes and biases the workspace
    // starts with; nothing reads them.
    if (!axes || element.coordinate < 0) continue;
    ws.motion_angular[k] = rel.angular_axis;
    ws.motion_linear[k] = rel.linear_axis;
    ws.bias_angular[k] = rel.angular_bias;
    ws.bias_linear[k] = rel.linear_bias;
  }
}

}  // namespace

template <class Scalar>
void frameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                KinematicsLevel level) {
  const bool accelerations = level == KinematicsLevel::Acceleration;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Vector3<Scalar> r = ws.position[s] - ws.position[e];  // r_s/e in ground axes
    const Vector3<Scalar>& we = ws.angular_velocity[e];
    if (element.coordinate < 0) {  // (20)-(21) of a rigid offset: no relative rate, no term in it
      ws.angular_velocity[s] = we;
      ws.velocity[s] = ws.velocity[e] + we.cross(r);
      if (!accelerations) continue;
      ws.angular_acceleration[s] = ws.angular_acceleration[e];
      ws.acceleration[s] = ws.acceleration[e] + ws.angular_acceleration[e].cross(r) + we.cross(we.cross(r));
      continue;
    }
    const Scalar& vi = v[element.coordinate];
    const Vector3<Scalar>& Sw = ws.motion_angular[k];
    const Vector3<Scalar>& Sv = ws.motion_linear[k];
    const Vector3<Scalar> w_rel = Sw * vi;
    const Vector3<Scalar> v_rel = Sv * vi;
    ws.angular_velocity[s] = we + w_rel;                    // (21)
    ws.velocity[s] = ws.velocity[e] + we.cross(r) + v_rel;  // (20)
    if (!accelerations) continue;
    const Scalar& ai = a[element.coordinate];
    const Scalar vi2 = vi * vi;
    ws.angular_acceleration[s] = ws.angular_acceleration[e] + we.cross(w_rel) + Sw * ai + ws.bias_angular[k] * vi2;
    ws.acceleration[s] = ws.acceleration[e] + ws.angular_acceleration[e].cross(r) + we.cross(we.cross(r)) +
                         Scalar(2) * we.cross(v_rel) + Sv * ai + ws.bias_linear[k] * vi2;
  }
}

template <class Scalar>
void frameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a) {
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    ws.angular_velocity[s].setZero();
    ws.velocity[s].setZero();
    const Vector3<Scalar>& alpha_e = ws.angular_acceleration[e];
    const Vector3<Scalar> r = ws.position[s] - ws.position[e];
    if (element.coordinate < 0) {  // (20)-(21) with q̇ = 0 and no joint rate
      ws.angular_acceleration[s] = alpha_e;
      ws.acceleration[s] = ws.acceleration[e] + alpha_e.cross(r);
      continue;
    }
    const Scalar& ai = a[element.coordinate];
    ws.angular_acceleration[s] = alpha_e + ws.motion_angular[k] * ai;
    ws.acceleration[s] = ws.acceleration[e] + alpha_e.cross(r) + ws.motion_linear[k] * ai;
  }
}

template <class Scalar>
void forwardKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                       const VectorX<Scalar>& v, const VectorX<Scalar>& a, KinematicsLevel level) {
  const bool rates = level != KinematicsLevel::Position;
  geometry(model, ws, q, rates);
  if (rates) frameRates(model, ws, v, a, level);
}

template <class Scalar>
void frameGeometry(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q) {
  geometry(model, ws, q, true);
}

void unitRateTwist(const Model& model, Workspace<double>& ws, int coordinate, FrameIndex frame, bool moved) {
  const auto f = static_cast<std::size_t>(frame);
  if (!moved) {
    ws.angular_velocity[f].setZero();
    ws.velocity[f].setZero();
    return;
  }
  const auto k = static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(coordinate)].element);
  const auto exit = static_cast<std::size_t>(model.elements()[k].exit);
  ws.angular_velocity[f] = ws.motion_angular[k];                                                      // (21)
  ws.velocity[f] = ws.motion_linear[k] + ws.motion_angular[k].cross(ws.position[f] - ws.position[exit]);  // (20)
}

template void frameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&, const VectorX<double>&,
                                 KinematicsLevel);
template void frameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                  const VectorX<AdScalar>&, KinematicsLevel);
template void frameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
template void frameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&);
template void frameGeometry<double>(const Model&, Workspace<double>&, const VectorX<double>&);
template void forwardKinematics<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                        const VectorX<double>&, const VectorX<double>&, KinematicsLevel);
template void forwardKinematics<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                          const VectorX<AdScalar>&, const VectorX<AdScalar>&, KinematicsLevel);

}  // namespace mbsopt
