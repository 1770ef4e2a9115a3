#include "dynamics/planar_recursions.hpp"

namespace mbsopt {

// Each acceleration is written as one expression: the terms of the pass at rest, in its order
// (a_e + α_e × r + S_v q̈), plus the terms in q̇, exact zeros at q̇ = 0, in a group of their own. Both
// passes then give the same bits at q̇ = 0 (tests/test_tramway.cpp); the two groups are independent
// chains of products (the double pass is bound by their latency, frame after frame); and an AD
// scalar's derivatives are evaluated in one loop over the whole expression.

template <class Scalar>
void planarFrameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                      KinematicsLevel level) {
  const bool accelerations = level == KinematicsLevel::Acceleration;
  const auto& elements = model.elements();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const KinematicElement& element = elements[k];
    const auto e = static_cast<std::size_t>(element.entry);
    const auto s = static_cast<std::size_t>(element.exit);
    const Scalar rx = ws.position[s].x() - ws.position[e].x();  // r_s/e in the plane
    const Scalar ry = ws.position[s].y() - ws.position[e].y();
    const Scalar& we = ws.angular_velocity[e].z();
    const Scalar& alpha_e = ws.angular_acceleration[e].z();
    if (element.coordinate < 0) {  // (20)-(21) of a rigid offset: ω_e × r, α_e × r + ω_e × (ω_e × r)
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
    const Scalar& Sw = ws.motion_angular[k].z();
    const Scalar& Svx = ws.motion_linear[k].x();
    const Scalar& Svy = ws.motion_linear[k].y();
    const Scalar v_rel_x = Svx * vi, v_rel_y = Svy * vi;
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
    const Scalar rx = ws.position[s].x() - ws.position[e].x();
    const Scalar ry = ws.position[s].y() - ws.position[e].y();
    const Scalar& alpha_e = ws.angular_acceleration[e].z();
    ws.angular_velocity[s].z() = Scalar(0);
    ws.velocity[s].x() = Scalar(0);
    ws.velocity[s].y() = Scalar(0);
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
    if (element.coordinate >= 0)  // (24)
      f[element.coordinate] += ws.motion_linear[k].x() * fx + ws.motion_linear[k].y() * fy + ws.motion_angular[k].z() * mz;
    ws.moment[e].z() += mz + ((ws.position[s].x() - ws.position[e].x()) * fy - (ws.position[s].y() - ws.position[e].y()) * fx);
    ws.force[e].x() += fx;
    ws.force[e].y() += fy;
  }
}

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
