#include "dynamics/kinematics.hpp"
#include "dynamics/overloaded.hpp"

#include <cmath>

namespace mbsopt {

namespace {

/// Exit frame relative to entry frame, all vectors in entry-frame axes.
template <class Scalar>
struct RelativeMotion {
  Matrix3<Scalar> rotation = Matrix3<Scalar>::Identity();
  Vector3<Scalar> translation = Vector3<Scalar>::Zero();
  Vector3<Scalar> angular_axis = Vector3<Scalar>::Zero();  ///< ∂ω_rel/∂q̇
  Vector3<Scalar> linear_axis = Vector3<Scalar>::Zero();   ///< ∂v_rel/∂q̇
  Vector3<Scalar> angular_bias = Vector3<Scalar>::Zero();  ///< α_rel − angular_axis·q̈
  Vector3<Scalar> linear_bias = Vector3<Scalar>::Zero();   ///< a_rel − linear_axis·q̈
};

template <class Scalar>
RelativeMotion<Scalar> relativeMotion(const ElementKind& kind, const Scalar& q, const Scalar& qd, bool rates) {
  RelativeMotion<Scalar> m;
  std::visit(Overloaded{
                 [&](const Offset& e) {
                   m.rotation = e.rotation.template cast<Scalar>();
                   m.translation = e.translation.template cast<Scalar>();
                 },
                 [&](const RevoluteJoint& e) {
                   m.rotation = axisRotation(e.axis, q);
                   m.angular_axis = e.axis.template cast<Scalar>();
                 },
                 [&](const PrismaticJoint& e) {
                   m.linear_axis = e.axis.template cast<Scalar>();
                   m.translation = m.linear_axis * q;
                 },
                 [&](const CurveSliderJoint& e) {
                   // Exact geometry at the value of s, carried to first order in s for derivative types:
                   // dr/ds = t, dψ/ds = κ, dκ/ds = κ'; piecewise κ'' = 0.
                   using std::cos;
                   using std::sin;
                   const TrackPoint point = e.track->at(valueOf(q));
                   const Scalar ds = q - Scalar(valueOf(q));
                   const Scalar heading = Scalar(point.heading) + Scalar(point.curvature) * ds;
                   const Scalar curvature = Scalar(point.curvature) + Scalar(point.curvature_derivative) * ds;
                   const Vector3<Scalar> tangent(cos(heading), sin(heading), Scalar(0));
                   const Vector3<Scalar> normal(-sin(heading), cos(heading), Scalar(0));
                   const bool rotates = e.orientation == SliderOrientation::FollowTrack;
                   m.translation = point.position.template cast<Scalar>() + point.tangent().template cast<Scalar>() * ds;
                   m.linear_axis = tangent;
                   if (rates) m.linear_bias = curvature * qd * qd * normal;  // a = t s̈ + κ ṡ² n
                   if (!rotates) return;
                   m.rotation = axisRotation(Eigen::Vector3d::UnitZ(), heading);
                   m.angular_axis = Vector3<Scalar>(Scalar(0), Scalar(0), curvature);
                   if (rates)  // α = (κ s̈ + κ' ṡ²) z
                     m.angular_bias = Vector3<Scalar>(Scalar(0), Scalar(0), Scalar(point.curvature_derivative) * qd * qd);
                 }},
             kind);
  return m;
}

}  // namespace

template <class Scalar>
void forwardKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                       const VectorX<Scalar>& v, const VectorX<Scalar>& a, KinematicsLevel level) {
  const bool rates = level != KinematicsLevel::Position;
  const bool accelerations = level == KinematicsLevel::Acceleration;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const bool active = element.coordinate >= 0;
    const auto i = static_cast<Eigen::Index>(element.coordinate);
    const Scalar qi = active ? q[i] : Scalar(0);
    const Scalar vi = active && rates ? v[i] : Scalar(0);
    const RelativeMotion<Scalar> rel = relativeMotion(element.kind, qi, vi, rates);

    const Matrix3<Scalar>& Re = ws.rotation[e];
    const Vector3<Scalar> r = Re * rel.translation;  // r_s/e in ground axes
    ws.rotation[s] = Re * rel.rotation;
    ws.position[s] = ws.position[e] + r;
    if (!rates) continue;

    const Vector3<Scalar> Sw = Re * rel.angular_axis;
    const Vector3<Scalar> Sv = Re * rel.linear_axis;
    ws.motion_angular[k] = Sw;
    ws.motion_linear[k] = Sv;
    const Vector3<Scalar> w_rel = Sw * vi;
    const Vector3<Scalar> v_rel = Sv * vi;
    const Vector3<Scalar>& we = ws.angular_velocity[e];
    ws.angular_velocity[s] = we + w_rel;                  // (21)
    ws.velocity[s] = ws.velocity[e] + we.cross(r) + v_rel;  // (20)
    if (!accelerations) continue;

    const Scalar ai = active ? a[i] : Scalar(0);
    ws.angular_acceleration[s] = ws.angular_acceleration[e] + we.cross(w_rel) + Sw * ai + Re * rel.angular_bias;
    ws.acceleration[s] = ws.acceleration[e] + ws.angular_acceleration[e].cross(r) + we.cross(we.cross(r)) +
                         Scalar(2) * we.cross(v_rel) + Sv * ai + Re * rel.linear_bias;
  }
}

void velocityPass(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& v) {
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const double vi = element.coordinate >= 0 ? v[element.coordinate] : 0.0;
    const Eigen::Vector3d& we = ws.angular_velocity[e];
    ws.angular_velocity[s] = we + ws.motion_angular[k] * vi;
    ws.velocity[s] = ws.velocity[e] + we.cross(ws.position[s] - ws.position[e]) + ws.motion_linear[k] * vi;
  }
}

template void forwardKinematics<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                        const VectorX<double>&, const VectorX<double>&, KinematicsLevel);
template void forwardKinematics<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                          const VectorX<AdScalar>&, const VectorX<AdScalar>&, KinematicsLevel);

}  // namespace mbsopt
