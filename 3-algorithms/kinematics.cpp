#include "mbsopt/algorithms/kinematics.hpp"

#include <cmath>
#include <string>

#include "mbsopt/model/overloaded.hpp"
#include "mbsopt/algorithms/ball_chart.hpp"
#include "mbsopt/algorithms/planar_recursions.hpp"
#include "mbsopt/algorithms/track_state.hpp"

namespace mbsopt {

namespace {

/// The exit frame of element k from its entry frame (rotation R_e, position p_e) at coordinate q,
/// into ws: its rotation and position, a curve slider's track at s, and with `axes` its joint axes
/// and biases in ground axes (∂ω_rel/∂q̇, ∂v_rel/∂q̇ and (α_rel − ∂ω_rel/∂q̇ q̈)/q̇², (a_rel −
/// ∂v_rel/∂q̇ q̈)/q̇²). Only what an element kind can make non-zero is written: the rest stays the
/// zeros the workspace starts with (an element keeps its kind), and costs no product.
template <class Scalar>
void placeExit(const Model& model, const ElementKind& kind, std::size_t k, std::size_t e, std::size_t s,
               const Scalar& q, bool axes, Workspace<Scalar>& ws) {
  const Matrix3<Scalar>& Re = ws.rotation[e];
  std::visit(Overloaded{
                 [&](const Offset& o) {
                   // The translation carries derivatives only in a pass seeded in it.
                   const Vector3<Scalar> translation = seedsAny(ws, o.translation)
                                                           ? Vector3<Scalar>(Re * parameter(model, ws, o.translation))
                                                           : Vector3<Scalar>(Re * model.vector(o.translation));
                   if (o.turn && seeds(ws, o.turn->angle))  // R(axis, angle) with its derivative
                     ws.rotation[s] = turnedAbout(Re, o.turn->axis, parameter(model, ws, o.turn->angle));
                   else
                     ws.rotation[s] = o.rotates ? Matrix3<Scalar>(Re * o.rotation) : Re;
                   ws.position[s] = ws.position[e] + translation;
                 },
                 [&](const RevoluteJoint& j) {
                   ws.rotation[s] = turnedAbout(Re, j.axis, q);
                   ws.position[s] = ws.position[e];
                   if (axes) ws.motion_angular[k] = Re * j.axis;
                 },
                 [&](const PrismaticJoint& j) {
                   const Vector3<Scalar> translation = Re * (j.axis * q);
                   ws.rotation[s] = Re;
                   ws.position[s] = ws.position[e] + translation;
                   if (axes) ws.motion_linear[k] = Re * j.axis;
                 },
                 [&](const CurveSliderJoint& j) {
                   // dr/ds = t to first order, as the heading and curvature (trackAt).
                   const TrackPointTpl<Scalar> track = trackAt(model, ws, j.track, q);
                   const Scalar& curvature = track.curvature;
                   const Scalar& cos_heading = track.cos_heading;
                   const Scalar& sin_heading = track.sin_heading;
                   ws.slider_track[k] = {cos_heading, sin_heading, curvature};
                   ws.position[s] = ws.position[e] + Re * track.position;
                   const bool turns = j.orientation != SliderOrientation::Translate;
                   if (axes) {
                     ws.motion_linear[k] = Re * Vector3<Scalar>(cos_heading, sin_heading, Scalar(0));
                     ws.bias_linear[k] = Re * (curvature * Vector3<Scalar>(-sin_heading, cos_heading, Scalar(0)));  // a = t s̈ + κ ṡ² n
                     if (turns) {
                       ws.motion_angular[k] = Re * Vector3<Scalar>(Scalar(0), Scalar(0), curvature);
                       // α = (κ s̈ + κ' ṡ²) z
                       ws.bias_angular[k] = Re * Vector3<Scalar>(Scalar(0), Scalar(0), track.curvature_derivative);
                     }
                   }
                   ws.rotation[s] = turns ? turnedAbout(Re, Eigen::Vector3d::UnitZ(), cos_heading, sin_heading) : Re;
                 },
                 [](const BallJointComponent&) {}},  // placed by placeBall, all three at once
             kind);
}

/// The ball joint of elements k (its x), k + 1 and k + 2 at its rotation vector φ (ball_chart.hpp):
/// the two frames inside it at its entry frame's place and in its axes, the exit turned by R(φ),
/// and with `axes` the columns of R_e J(φ) as the three motion axes and the chart for the rate stage.
template <class Scalar>
void placeBall(const Model& model, std::size_t k, const VectorX<Scalar>& q, bool axes, Workspace<Scalar>& ws) {
  const auto& elements = model.elements();
  const KinematicElement& x = elements[k];
  const Vector3<Scalar> phi = q.template segment<3>(x.coordinate);
  const Scalar theta2 = phi.squaredNorm();
  if (valueOf(theta2) > kBallChartLimit * kBallChartLimit)
    throw DegenerateElementError(
        x.name, "the ball joint of " + x.name + ", " + elements[k + 1].name + ", " + elements[k + 2].name +
                    " has turned by |φ| = " + std::to_string(std::sqrt(valueOf(theta2))) +
                    " rad from its reference, beyond 1.8π, where its rotation-vector chart ends (a joint that spins "
                    "about one axis without end is a `spherical` one spinning about its x axis)");
  const BallChartCoefficients<Scalar> chart = ballChartCoefficients(theta2);
  const Matrix3<Scalar> K = crossMatrixOf(phi);
  const Matrix3<Scalar> K2 = crossSquaredOf(phi, theta2);
  const auto e = static_cast<std::size_t>(x.entry);
  const Matrix3<Scalar>& Re = ws.rotation[e];
  for (std::size_t c = 0; c < 3; ++c) ws.position[static_cast<std::size_t>(elements[k + c].exit)] = ws.position[e];
  for (std::size_t c = 0; c < 2; ++c) ws.rotation[static_cast<std::size_t>(elements[k + c].exit)] = Re;
  Matrix3<Scalar> turn = chart.sinc * K + chart.alpha * K2;  // R(φ) = 1 + s K + α K²
  turn.diagonal().array() += Scalar(1);
  const auto exit = static_cast<std::size_t>(elements[k + 2].exit);
  ws.rotation[exit] = Re * turn;
  if (!axes) return;
  Matrix3<Scalar> jacobian = chart.alpha * K + chart.beta * K2;  // J(φ) = 1 + α K + β K²
  jacobian.diagonal().array() += Scalar(1);
  const Matrix3<Scalar> motion = Re * jacobian;
  for (std::size_t c = 0; c < 3; ++c) ws.motion_angular[k + c] = motion.col(static_cast<Eigen::Index>(c));
  ws.ball_chart[k + 2] = {Re * phi, chart.beta, chart.alpha_rate, chart.beta_rate};
}

/// The entry frame of the ball joint whose `ball` element k is.
std::size_t ballEntry(const Model& model, std::size_t k, const BallJointComponent& ball) {
  return static_cast<std::size_t>(model.elements()[k - static_cast<std::size_t>(ball.component)].entry);
}

/// R_e J̇ φ̇ of the ball joint whose z element is k, from the chart its geometry stage left in ws.
template <class Scalar>
Vector3<Scalar> ballAccelerationBias(const Model& model, const Workspace<Scalar>& ws, const VectorX<Scalar>& v,
                                     std::size_t k) {
  const KinematicElement& x = model.elements()[k - 2];
  const BallChart<Scalar>& chart = ws.ball_chart[k];
  const Vector3<Scalar> phi_rate = v.template segment<3>(x.coordinate);
  const Vector3<Scalar> rate = ws.rotation[static_cast<std::size_t>(x.entry)] * phi_rate;
  return ballRateBias(chart.rotation_vector, rate, chart.beta, chart.alpha_rate, chart.beta_rate);
}

template <class Scalar>
void geometry(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, bool axes) {
  ws.body_axes_current = false;
  if (model.planar()) return planarGeometry(model, ws, q, axes);
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    if (const auto* ball = std::get_if<BallJointComponent>(&element.kind)) {
      if (ball->component == 0) placeBall(model, k, q, axes, ws);
      continue;
    }
    const Scalar qi = element.coordinate >= 0 ? q[element.coordinate] : Scalar(0);
    placeExit(model, element.kind, k, static_cast<std::size_t>(element.entry), static_cast<std::size_t>(element.exit), qi, axes,
              ws);
  }
}

}  // namespace

template <class Scalar>
void spatialFrameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
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
    // A ball's three rates each turn its exit relative to the ball's entry frame, whose rate is then
    // the one in ω_e × ω_rel; J̇ φ̇ comes with the last of them.
    const auto* ball = std::get_if<BallJointComponent>(&element.kind);
    const Vector3<Scalar>& w_turning = ball ? ws.angular_velocity[ballEntry(model, k, *ball)] : we;
    ws.angular_acceleration[s] =
        ws.angular_acceleration[e] + w_turning.cross(w_rel) + Sw * ai + ws.bias_angular[k] * vi2;
    if (ball && ball->component == 2) ws.angular_acceleration[s] += ballAccelerationBias(model, ws, v, k);
    ws.acceleration[s] = ws.acceleration[e] + ws.angular_acceleration[e].cross(r) + we.cross(we.cross(r)) +
                         Scalar(2) * we.cross(v_rel) + Sv * ai + ws.bias_linear[k] * vi2;
  }
}

template <class Scalar>
void spatialFrameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a) {
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
void frameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                KinematicsLevel level) {
  if (model.planar()) planarFrameRates(model, ws, v, a, level);
  else spatialFrameRates(model, ws, v, a, level);
}

template <class Scalar>
void frameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a) {
  if (model.planar()) planarFrameAccelerationsAtRest(model, ws, a);
  else spatialFrameAccelerationsAtRest(model, ws, a);
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

template void spatialFrameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                        const VectorX<double>&, KinematicsLevel);
template void spatialFrameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                          const VectorX<AdScalar>&, KinematicsLevel);
template void spatialFrameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
template void spatialFrameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&);
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
