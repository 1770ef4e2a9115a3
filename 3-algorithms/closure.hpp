// Loop-closure equations of the cut joints (34): b(q, t) = 0, with their exact first and second
// time derivatives, computed from the frame kinematics of the forward recursion. Each cut joint is
// a set of point coincidences (p_a − p_b = 0) and of orthogonalities between unit vectors fixed in
// the two frames (u_a·w_b = 0).
#pragma once

#include "mbsopt/algorithms/kinematics.hpp"

namespace mbsopt {

/// b (level Position), ḃ = B q̇ + ∂b/∂t (Velocity) or b̈ (Acceleration), for every cut joint in
/// model order. Needs forwardKinematics at least at that level. `out` has constraintCount() rows.
template <class Scalar>
void closureEquations(const Model& model, const Workspace<Scalar>& ws, Derivative level, VectorX<Scalar>& out);

/// Adds the generalised constraint forces Bᵀλ (36) as wrenches on the cut frames, so the backward
/// recursion maps them to joint space (∂(λᵀb)/∂q = Bᵀλ by virtual work). Needs Position level.
template <class Scalar>
void addConstraintWrenches(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& lambda);

/// The coefficients c(q) of a cut-reaction sensor's value y = c·λ: one per closure equation of the
/// model, zero outside the rows of the sensor's cut. The cut transmits to its frame b, from frame a's
/// side, the force λ_p of its coincidence rows p_a − p_b and the torque Σ λ_r u_r × w_r of its
/// orthogonality rows u_r·w_r (Bᵀλ of (36) on its frames, as addConstraintWrenches applies them);
/// y is that force's or torque's component along axis `component` of frame a. Needs
/// forwardKinematics at Position level.
template <class Scalar>
void reactionCoefficients(const Model& model, const Workspace<Scalar>& ws, const CutReactionSensor& sensor,
                          VectorX<Scalar>& c);

/// The closure equations of a weld cut (three orthogonalities) also hold when frame b is turned by
/// 180° (or 120° about a diagonal) relative to frame a. Throws std::invalid_argument naming the cut
/// when the frames of a weld cut are turned by more than 90° from each other (trace(R_aᵀR_b) ≤ 1).
/// Needs forwardKinematics at Position level.
void checkWeldOrientations(const Model& model, const Workspace<double>& ws);

extern template void closureEquations<double>(const Model&, const Workspace<double>&, Derivative,
                                              VectorX<double>&);
extern template void closureEquations<AdScalar>(const Model&, const Workspace<AdScalar>&, Derivative,
                                                VectorX<AdScalar>&);
extern template void addConstraintWrenches<double>(const Model&, Workspace<double>&, const VectorX<double>&);
extern template void reactionCoefficients<double>(const Model&, const Workspace<double>&, const CutReactionSensor&,
                                                  VectorX<double>&);
extern template void reactionCoefficients<AdScalar>(const Model&, const Workspace<AdScalar>&, const CutReactionSensor&,
                                                    VectorX<AdScalar>&);
extern template void addConstraintWrenches<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&);

}  // namespace mbsopt
