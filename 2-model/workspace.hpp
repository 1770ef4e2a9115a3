// Mutable per-evaluation buffers (the "data" of the model/workspace split, docs/design.md §2). One
// workspace per thread: evaluations on separate workspaces may run in parallel.
#pragma once

#include <initializer_list>
#include <type_traits>
#include <utility>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/scalar.hpp"

namespace mbsopt {

/// The track geometry at a curve slider's coordinate that force elements reuse (track guidance):
/// the tangent's direction cosines and the curvature, with the derivatives of the pass.
template <class Scalar>
struct SliderTrack {
  Scalar cos_heading{0}, sin_heading{0}, curvature{0};  ///< cos ψ(s), sin ψ(s), κ(s)
};

/// What the rate stage needs of a ball joint's chart at φ (3-algorithms/ball_chart.hpp), set by the
/// geometry stage: φ in ground axes and the coefficients of J̇ φ̇ (ballRateBias).
template <class Scalar>
struct BallChart {
  Vector3<Scalar> rotation_vector = Vector3<Scalar>::Zero();  ///< R_e φ
  Scalar beta{0}, alpha_rate{0}, beta_rate{0};                ///< β(θ), α'(θ)/θ, β'(θ)/θ
};

template <class Scalar>
struct Workspace {
  explicit Workspace(const Model& model)
      : rotation(static_cast<std::size_t>(model.frameCount()), Matrix3<Scalar>::Identity()),
        position(rotation.size(), Vector3<Scalar>::Zero()),
        angular_velocity(rotation.size(), Vector3<Scalar>::Zero()),
        velocity(rotation.size(), Vector3<Scalar>::Zero()),
        angular_acceleration(rotation.size(), Vector3<Scalar>::Zero()),
        acceleration(rotation.size(), Vector3<Scalar>::Zero()),
        force(rotation.size(), Vector3<Scalar>::Zero()),
        moment(rotation.size(), Vector3<Scalar>::Zero()),
        motion_angular(model.elements().size(), Vector3<Scalar>::Zero()),
        motion_linear(model.elements().size(), Vector3<Scalar>::Zero()),
        bias_angular(model.elements().size(), Vector3<Scalar>::Zero()),
        bias_linear(model.elements().size(), Vector3<Scalar>::Zero()),
        body_centre(model.bodies().size(), Vector3<Scalar>::Zero()),
        body_inertia(model.bodies().size(), Matrix3<Scalar>::Zero()),
        slider_track(model.elements().size()),
        ball_chart(model.elements().size()) {}

  // Absolute kinematics of every frame, in ground axes (forward recursion).
  std::vector<Matrix3<Scalar>> rotation;
  std::vector<Vector3<Scalar>> position, angular_velocity, velocity, angular_acceleration, acceleration;
  // Wrench each frame must transmit to what lies beyond it, about its origin (backward recursion).
  std::vector<Vector3<Scalar>> force, moment;
  // Per active element: ∂ω_s/e/∂q̇ and ∂v_s/e/∂q̇ in ground axes, and the relative accelerations
  // not proportional to q̈, per q̇² (a curve slider's κ n and κ' z).
  std::vector<Vector3<Scalar>> motion_angular, motion_linear;
  std::vector<Vector3<Scalar>> bias_angular, bias_linear;
  // Per body, its centre of mass (from its frame's origin) and its inertia tensor in ground axes,
  // R c and R I Rᵀ: computed by the first wrench pass on a geometry and reused by the next ones on
  // it (a pass of the residual and the projections' passes share them). The geometry stage marks
  // them stale: like the geometry, they carry the seeds of the pass that computed it.
  std::vector<Vector3<Scalar>> body_centre;
  std::vector<Matrix3<Scalar>> body_inertia;
  bool body_axes_current = false;
  // Per element, for the curve sliders only: their track at s, set by the geometry stage.
  std::vector<SliderTrack<Scalar>> slider_track;
  // Per element, for the z element of each ball joint only: its chart at φ, set by the geometry stage.
  std::vector<BallChart<Scalar>> ball_chart;
  // Coordinates (q, q̇, q̈), multipliers λ and residual f of a pass whose inputs are seeded (AdScalar),
  // kept between passes so that repeated passes allocate nothing.
  VectorX<Scalar> seeded_q, seeded_v, seeded_a, seeded_lambda, seeded_f;
  /// Model parameters differentiated in this evaluation (AdScalar only): the parameter and the AD
  /// direction it is seeded in. Empty: none.
  std::vector<std::pair<ParameterIndex, int>> parameter_seeds;
  /// The model and the time of the state a pass evaluates, when a seeded parameter may be a number
  /// of a driven joint's motion (drivingCoordinate): the pass then seeds that joint's q, q̇, q̈ with
  /// their derivatives in it (seedDrivenMotions, 5-sensitivity/forward_ad.hpp). Null: never.
  const Model* driving_model = nullptr;
  double driving_time = 0.0;
};

/// to += v; on a planar model only the components in `carried`, those the planar backward recursion
/// carries (planar_recursions.hpp), so that the others are never written there and keep the
/// workspace's zeros.
template <class Scalar>
void addCarried(const Model& model, Vector3<Scalar>& to, const Vector3<Scalar>& v, std::initializer_list<int> carried) {
  if (!model.planar()) {
    to += v;
    return;
  }
  for (const int i : carried) to[i] += v[i];
}

/// Adds F to the force frame k transmits (on a planar model F_x and F_y), and M to its moment (M_z).
template <class Scalar>
void addForce(const Model& model, Workspace<Scalar>& ws, std::size_t k, const Vector3<Scalar>& force) {
  addCarried(model, ws.force[k], force, {0, 1});
}
template <class Scalar>
void addMoment(const Model& model, Workspace<Scalar>& ws, std::size_t k, const Vector3<Scalar>& moment) {
  addCarried(model, ws.moment[k], moment, {2});
}

/// A model parameter read into the evaluation's scalar: with a unit derivative in its direction
/// when ws.parameter_seeds names it (∂/∂b by forward AD of the same code), a constant otherwise.
template <class Scalar>
Scalar parameter(const Model& model, const Workspace<Scalar>& ws, ParameterIndex index) {
  Scalar out(model.value(index));
  if constexpr (!std::is_same_v<Scalar, double>) {
    for (const auto& [seeded, direction] : ws.parameter_seeds)
      if (seeded == index) out.derivatives()[direction] = 1.0;
  }
  return out;
}

/// The order-th time derivative of a time input at t (a spring's rest value or target, an actuation,
/// a driven joint's motion), its numbers read as model parameters: seeded where a pass differentiates
/// them. In double, Model::value(input, t, order) to the bit.
template <class Scalar>
Scalar timeValue(const Model& model, const Workspace<Scalar>& ws, const TimeInput& input, double t, int order = 0) {
  return timeFunctionDerivative<Scalar>(
      input.coefficients.size(), [&](std::size_t k) { return parameter(model, ws, input.coefficients[k]); },
      input.harmonics.size(),
      [&](std::size_t j, int which) { return parameter(model, ws, input.harmonics[j][static_cast<std::size_t>(which)]); },
      t, order);
}

template <class Scalar>
Vector3<Scalar> parameter(const Model& model, const Workspace<Scalar>& ws, const ParameterVector3& indices) {
  return {parameter(model, ws, indices[0]), parameter(model, ws, indices[1]), parameter(model, ws, indices[2])};
}

/// Whether ws.parameter_seeds names the parameter (never in double).
template <class Scalar>
bool seeds(const Workspace<Scalar>& ws, ParameterIndex index) {
  if constexpr (std::is_same_v<Scalar, double>) {
    return false;
  } else {
    for (const auto& [seeded, direction] : ws.parameter_seeds)
      if (seeded == index) return true;
    return false;
  }
}

/// Whether ws.parameter_seeds names one of the three (never in double): code that multiplies a
/// constant vector takes its cheaper path in double otherwise.
template <class Scalar>
bool seedsAny(const Workspace<Scalar>& ws, const ParameterVector3& indices) {
  return seeds(ws, indices[0]) || seeds(ws, indices[1]) || seeds(ws, indices[2]);
}

}  // namespace mbsopt
