#include "mbsopt/algorithms/planar_recursions.hpp"

#include <cmath>
#include <utility>
#include <variant>

#include "mbsopt/model/overloaded.hpp"
#include "mbsopt/algorithms/track_state.hpp"

namespace mbsopt {

// Each acceleration is written as one expression: the terms of the pass at rest, in its order
// (a_e + α_e × r + S_v q̈), plus the terms in q̇, exact zeros at q̇ = 0, in a group of their own. Both
// passes then give the same bits at q̇ = 0 (tests/8-design/test_tramway.cpp); the two groups are independent
// chains of products (the double pass is bound by their latency, frame after frame); and an AD
// scalar's derivatives are evaluated in one loop over the whole expression.

namespace {

/// The xy block of R_e turned about z by the angle of cosine c and sine s (R_e R_z): its first two
/// columns' first two rows, into those of `out`.
template <class Scalar>
void turnInPlane(const Matrix3<Scalar>& Re, const Scalar& c, const Scalar& s, Matrix3<Scalar>& out) {
  const Scalar r00 = Re(0, 0), r10 = Re(1, 0), r01 = Re(0, 1), r11 = Re(1, 1);
  out(0, 0) = r00 * c + r01 * s;
  out(1, 0) = r10 * c + r11 * s;
  out(0, 1) = r01 * c - r00 * s;
  out(1, 1) = r11 * c - r10 * s;
}

/// R_e's xy block into `out`'s.
template <class Scalar>
void copyPlaneBlock(const Matrix3<Scalar>& Re, Matrix3<Scalar>& out) {
  out(0, 0) = Re(0, 0);
  out(1, 0) = Re(1, 0);
  out(0, 1) = Re(0, 1);
  out(1, 1) = Re(1, 1);
}

/// Whether a hinge of a planar model turns about +z (its axis is +z or −z). Its exit frame sits on its
/// entry frame (r = 0) and it has no linear axis nor bias, so the recursions' terms in r, S_v and the
/// biases are exact zeros there, and S_ω q̇ = ±q̇: its rates and residual skip them, to the same values
/// (up to the sign of a zero).
bool turnsPositively(const RevoluteJoint& hinge) { return hinge.axis.z() > 0.0; }

/// The rate about z of a hinge's exit frame from its entry frame's and the joint's: entry ± joint
/// (ω from q̇, α from q̈).
template <class Scalar>
Scalar hingeRate(const RevoluteJoint& hinge, const Scalar& entry, const Scalar& joint) {
  return turnsPositively(hinge) ? Scalar(entry + joint) : Scalar(entry - joint);
}

/// R_e (x, y, ·) in the plane: the first two components of R_e v for v = (x, y, z), whose third is z.
template <class Scalar, class X, class Y>
std::pair<Scalar, Scalar> inPlane(const Matrix3<Scalar>& Re, const X& x, const Y& y) {
  return {Re(0, 0) * x + Re(0, 1) * y, Re(1, 0) * x + Re(1, 1) * y};
}

}  // namespace

template <class Scalar>
void planarGeometry(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, bool axes) {
  using std::cos;
  using std::sin;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Matrix3<Scalar>& Re = ws.rotation[e];
    const auto coordinate = [&]() -> const Scalar& { return q[element.coordinate]; };  // joints only
    std::visit(Overloaded{
                   [&](const Offset& o) {
                     // The translation carries derivatives only in a pass seeded in it.
                     const auto place = [&](const auto& translation) {
                       const auto [x, y] = inPlane(Re, translation.x(), translation.y());
                       ws.position[s] = Vector3<Scalar>(ws.position[e].x() + x, ws.position[e].y() + y,
                                                        ws.position[e].z() + translation.z());
                     };
                     if (seedsAny(ws, o.translation)) place(parameter(model, ws, o.translation));
                     else place(model.vector(o.translation));
                     if (o.turn && seeds(ws, o.turn->angle)) {  // about ±z (Model::planar): the angle ±θ
                       const Scalar angle = parameter(model, ws, o.turn->angle);
                       const Scalar c = cos(angle), sn = sin(angle);
                       turnInPlane(Re, c, o.turn->axis.z() > 0.0 ? sn : Scalar(-sn), ws.rotation[s]);
                     } else if (o.rotates) {
                       turnInPlane(Re, Scalar(o.rotation(0, 0)), Scalar(o.rotation(1, 0)), ws.rotation[s]);
                     } else {
                       copyPlaneBlock(Re, ws.rotation[s]);
                     }
                   },
                   [&](const RevoluteJoint& j) {  // about ±z: the angle ±q
                     const Scalar c = cos(coordinate()), sn = sin(coordinate());
                     turnInPlane(Re, c, turnsPositively(j) ? sn : Scalar(-sn), ws.rotation[s]);
                     ws.position[s] = ws.position[e];
                     if (axes) ws.motion_angular[k].z() = Scalar(j.axis.z());
                   },
                   [&](const PrismaticJoint& j) {
                     const auto [x, y] = inPlane(Re, j.axis.x(), j.axis.y());
                     const Scalar& qi = coordinate();
                     ws.position[s] = Vector3<Scalar>(ws.position[e].x() + x * qi, ws.position[e].y() + y * qi,
                                                      ws.position[e].z());
                     copyPlaneBlock(Re, ws.rotation[s]);
                     if (axes) {
                       ws.motion_linear[k].x() = x;
                       ws.motion_linear[k].y() = y;
                     }
                   },
                   [&](const CurveSliderJoint& j) {
                     // As placeExit (kinematics.cpp): dr/ds = t to first order, as the heading and curvature.
                     const TrackPointTpl<Scalar> track = trackAt(model, ws, j.track, coordinate());
                     ws.slider_track[k] = {track.cos_heading, track.sin_heading, track.curvature};
                     const auto [x, y] = inPlane(Re, track.position.x(), track.position.y());
                     ws.position[s] = Vector3<Scalar>(ws.position[e].x() + x, ws.position[e].y() + y,
                                                      ws.position[e].z() + track.position.z());
                     const bool turns = j.orientation != SliderOrientation::Translate;
                     if (axes) {
                       const auto [tx, ty] = inPlane(Re, track.cos_heading, track.sin_heading);  // a = t s̈ + κ ṡ² n
                       ws.motion_linear[k].x() = tx;
                       ws.motion_linear[k].y() = ty;
                       ws.bias_linear[k].x() = -(track.curvature * ty);
                       ws.bias_linear[k].y() = track.curvature * tx;
                       if (turns) {  // ω = κ ṡ z, α = (κ s̈ + κ' ṡ²) z
                         ws.motion_angular[k].z() = track.curvature;
                         ws.bias_angular[k].z() = track.curvature_derivative;
                       }
                     }
                     if (turns) turnInPlane(Re, track.cos_heading, track.sin_heading, ws.rotation[s]);
                     else copyPlaneBlock(Re, ws.rotation[s]);
                   },
                   [](const BallJointComponent&) {}},  // never planar (Model::planar)
               element.kind);
  }
}

template <class Scalar>
void planarFrameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                      KinematicsLevel level) {
  const bool accelerations = level == KinematicsLevel::Acceleration;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Scalar& we = ws.angular_velocity[e].z();
    const Scalar& alpha_e = ws.angular_acceleration[e].z();
    if (element.coordinate < 0) {  // (20)-(21) of a rigid offset: ω_e × r, α_e × r + ω_e × (ω_e × r)
      const Scalar rx = ws.position[s].x() - ws.position[e].x();  // r_s/e in the plane
      const Scalar ry = ws.position[s].y() - ws.position[e].y();
      ws.angular_velocity[s].z() = we;
      ws.velocity[s].x() = ws.velocity[e].x() - we * ry;
      ws.velocity[s].y() = ws.velocity[e].y() + we * rx;
      if (!accelerations) continue;
      const Scalar we2 = we * we;
      ws.angular_acceleration[s].z() = alpha_e;
      ws.acceleration[s].x() = ws.acceleration[e].x() - alpha_e * ry - we2 * rx;
      ws.acceleration[s].y() = ws.acceleration[e].y() + alpha_e * rx - we2 * ry;
      continue;
    }
    const Scalar& vi = v[element.coordinate];
    if (const auto* hinge = std::get_if<RevoluteJoint>(&element.kind)) {  // (20)-(21) of a hinge: r = 0, S_v = 0
      ws.angular_velocity[s].z() = hingeRate(*hinge, we, vi);
      ws.velocity[s].x() = ws.velocity[e].x();
      ws.velocity[s].y() = ws.velocity[e].y();
      if (!accelerations) continue;
      const Scalar& ai = a[element.coordinate];
      ws.angular_acceleration[s].z() = hingeRate(*hinge, alpha_e, ai);
      ws.acceleration[s].x() = ws.acceleration[e].x();
      ws.acceleration[s].y() = ws.acceleration[e].y();
      continue;
    }
    const Scalar& Sw = ws.motion_angular[k].z();
    const Scalar& Svx = ws.motion_linear[k].x();
    const Scalar& Svy = ws.motion_linear[k].y();
    const Scalar v_rel_x = Svx * vi, v_rel_y = Svy * vi;
    if (element.entry == Model::ground) {  // the ground does not move: the terms in ω_e, α_e, v_e, a_e vanish
      ws.angular_velocity[s].z() = Sw * vi;
      ws.velocity[s].x() = v_rel_x;
      ws.velocity[s].y() = v_rel_y;
      if (!accelerations) continue;
      const Scalar& ai = a[element.coordinate];
      const Scalar vi2 = vi * vi;
      ws.angular_acceleration[s].z() = Sw * ai + ws.bias_angular[k].z() * vi2;
      ws.acceleration[s].x() = Svx * ai + ws.bias_linear[k].x() * vi2;
      ws.acceleration[s].y() = Svy * ai + ws.bias_linear[k].y() * vi2;
      continue;
    }
    const Scalar rx = ws.position[s].x() - ws.position[e].x();
    const Scalar ry = ws.position[s].y() - ws.position[e].y();
    ws.angular_velocity[s].z() = we + Sw * vi;                    // (21)
    ws.velocity[s].x() = ws.velocity[e].x() - we * ry + v_rel_x;  // (20)
    ws.velocity[s].y() = ws.velocity[e].y() + we * rx + v_rel_y;
    if (!accelerations) continue;
    // On top of the terms at rest: ω_e × (ω_e × r) = −ω_e² r, 2 ω_e × v_rel and the biases times q̇².
    const Scalar& ai = a[element.coordinate];
    const Scalar we2 = we * we, two_we = Scalar(2) * we, vi2 = vi * vi;
    ws.angular_acceleration[s].z() = (alpha_e + Sw * ai) + ws.bias_angular[k].z() * vi2;
    ws.acceleration[s].x() = (ws.acceleration[e].x() - alpha_e * ry + Svx * ai) +
                             (ws.bias_linear[k].x() * vi2 - we2 * rx - two_we * v_rel_y);
    ws.acceleration[s].y() = (ws.acceleration[e].y() + alpha_e * rx + Svy * ai) +
                             (ws.bias_linear[k].y() * vi2 - we2 * ry + two_we * v_rel_x);
  }
}

template <class Scalar>
void planarFrameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a) {
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Scalar& alpha_e = ws.angular_acceleration[e].z();
    ws.angular_velocity[s].z() = Scalar(0);
    ws.velocity[s].x() = Scalar(0);
    ws.velocity[s].y() = Scalar(0);
    if (const auto* hinge = std::get_if<RevoluteJoint>(&element.kind)) {  // r = 0, S_v = 0
      const Scalar& ai = a[element.coordinate];
      ws.angular_acceleration[s].z() = hingeRate(*hinge, alpha_e, ai);
      ws.acceleration[s].x() = ws.acceleration[e].x();
      ws.acceleration[s].y() = ws.acceleration[e].y();
      continue;
    }
    if (element.coordinate >= 0 && element.entry == Model::ground) {  // α_e = 0, a_e = 0
      const Scalar& ai = a[element.coordinate];
      ws.angular_acceleration[s].z() = ws.motion_angular[k].z() * ai;
      ws.acceleration[s].x() = ws.motion_linear[k].x() * ai;
      ws.acceleration[s].y() = ws.motion_linear[k].y() * ai;
      continue;
    }
    const Scalar rx = ws.position[s].x() - ws.position[e].x();
    const Scalar ry = ws.position[s].y() - ws.position[e].y();
    if (element.coordinate < 0) {  // (20)-(21) at q̇ = 0 without joint rate: α_e, a_e + α_e × r
      ws.angular_acceleration[s].z() = alpha_e;
      ws.acceleration[s].x() = ws.acceleration[e].x() - alpha_e * ry;
      ws.acceleration[s].y() = ws.acceleration[e].y() + alpha_e * rx;
      continue;
    }
    const Scalar& ai = a[element.coordinate];
    ws.angular_acceleration[s].z() = alpha_e + ws.motion_angular[k].z() * ai;
    ws.acceleration[s].x() = ws.acceleration[e].x() - alpha_e * ry + ws.motion_linear[k].x() * ai;
    ws.acceleration[s].y() = ws.acceleration[e].y() + alpha_e * rx + ws.motion_linear[k].y() * ai;
  }
}

template <class Scalar>
void planarBodyWrenches(const Model& model, Workspace<Scalar>& ws, const Vector3<Scalar>& g, bool moving) {
  const auto& bodies = model.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const auto k = static_cast<std::size_t>(body.frame);
    const Scalar& alpha = ws.angular_acceleration[k].z();
    const Scalar& cx = ws.body_centre[i].x();
    const Scalar& cy = ws.body_centre[i].y();
    const Scalar mass = parameter(model, ws, body.mass);
    Scalar fx, fy;
    if (moving) {
      const Scalar& w = ws.angular_velocity[k].z();
      const Scalar w2 = w * w;
      fx = mass * ((ws.acceleration[k].x() - alpha * cy - w2 * cx) - g.x());
      fy = mass * ((ws.acceleration[k].y() + alpha * cx - w2 * cy) - g.y());
    } else {
      fx = mass * ((ws.acceleration[k].x() - alpha * cy) - g.x());
      fy = mass * ((ws.acceleration[k].y() + alpha * cx) - g.y());
    }
    ws.force[k].x() += fx;
    ws.force[k].y() += fy;
    ws.moment[k].z() += parameter(model, ws, body.moments_of_inertia[2]) * alpha + (cx * fy - cy * fx);
  }
}

template <class Scalar>
void planarElementResiduals(const Model& model, Workspace<Scalar>& ws, VectorX<Scalar>& f) {
  const auto& elements = model.elements();
  for (std::size_t k = elements.size(); k-- > 0;) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Scalar& fx = ws.force[s].x();
    const Scalar& fy = ws.force[s].y();
    const Scalar& mz = ws.moment[s].z();
    if (const auto* hinge = std::get_if<RevoluteJoint>(&element.kind)) {  // (22)-(24) with r = 0, S_v = 0
      if (turnsPositively(*hinge)) f[element.coordinate] += mz;
      else f[element.coordinate] -= mz;
      ws.moment[e].z() += mz;
      ws.force[e].x() += fx;
      ws.force[e].y() += fy;
      continue;
    }
    if (element.coordinate >= 0)  // (24)
      f[element.coordinate] +=
          ws.motion_linear[k].x() * fx + ws.motion_linear[k].y() * fy + ws.motion_angular[k].z() * mz;
    if (element.entry == Model::ground) continue;  // nothing reads the ground's wrench
    const Scalar rx = ws.position[s].x() - ws.position[e].x(), ry = ws.position[s].y() - ws.position[e].y();
    ws.moment[e].z() += mz + (rx * fy - ry * fx);  // (23): M_e += M_s + (r × F_s)_z
    ws.force[e].x() += fx;  // (22)
    ws.force[e].y() += fy;
  }
}

template void planarGeometry<double>(const Model&, Workspace<double>&, const VectorX<double>&, bool);
template void planarGeometry<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&, bool);
template void planarFrameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                       const VectorX<double>&, KinematicsLevel);
template void planarFrameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                         const VectorX<AdScalar>&, KinematicsLevel);
template void planarFrameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
template void planarFrameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&);
template void planarBodyWrenches<double>(const Model&, Workspace<double>&, const Vector3<double>&, bool);
template void planarBodyWrenches<AdScalar>(const Model&, Workspace<AdScalar>&, const Vector3<AdScalar>&, bool);
template void planarElementResiduals<double>(const Model&, Workspace<double>&, VectorX<double>&);
template void planarElementResiduals<AdScalar>(const Model&, Workspace<AdScalar>&, VectorX<AdScalar>&);

}  // namespace mbsopt
