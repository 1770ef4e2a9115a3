// The recursions of a planar model (Model::planar), where every angular velocity and acceleration
// is along z and every linear one in the xy plane.
// - The geometric stage: every rotation is about z, so only the xy block of a rotation changes with q
//   (turned by cos and sin) and the joints' axes S_ω = ±z are constants; the other entries of the
//   rotations, and the axes' out-of-plane components, keep the values a workspace starts with
//   (those of the identity, and zeros), which no stage changes on a planar model.
// - The rate stage of the forward recursion (20)-(21): the cross products of the spatial recursion
//   reduce to ω × r = ω (−r_y, r_x) and ω × (ω × r) = −ω² (r_x, r_y), and ω_e × ω_rel vanishes: about
//   a third of its products. Its results are the spatial recursion's, whose out-of-plane terms are
//   exact zeros on such a model (0 · x), up to the order of the remaining operations. The
//   out-of-plane components of the rates are not written: they keep the zeros a workspace starts
//   with, which no other stage changes on a planar model.
// - The backward recursion (22)-(24) carries only the wrench components the residual rows read: the
//   force in the plane and the moment about z (a joint's axes S_ω along z and S_v in the plane,
//   M_z,e = M_z,s + (r × F)_z needing F in the plane only). A body's inertia then enters by its I_zz
//   alone, (R I Rᵀ)_zz = I_zz for a rotation R about z, and ω × Iω has no z component. The other
//   components of ws.force and ws.moment are not carried: no stage writes them on a planar model
//   (the force elements and cut joints add through addForce and addMoment, workspace.hpp), and
//   they keep the zeros a workspace starts with.
#pragma once

#include "mbsopt/algorithms/kinematics.hpp"

namespace mbsopt {

/// The geometric stage of forwardKinematics (kinematics.hpp) for a planar model: rotations,
/// positions and curve sliders' tracks, and with `axes` the joints' axes and biases.
template <class Scalar>
void planarGeometry(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, bool axes);
/// frameRates (kinematics.hpp) for a planar model.
template <class Scalar>
void planarFrameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                      KinematicsLevel level);
/// frameAccelerationsAtRest (kinematics.hpp) for a planar model.
template <class Scalar>
void planarFrameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a);

/// The body wrenches of addBodyWrenches (residual.cpp) in the plane, with gravity g: m (a_c − g) in
/// the plane and I_zz α + (c × F)_z about z, with a_c = a + α × c + ω × (ω × c) (`moving`) or
/// a + α × c (at rest); ws.body_centre holds each body's R c.
template <class Scalar>
void planarBodyWrenches(const Model& model, Workspace<Scalar>& ws, const Vector3<Scalar>& g, bool moving);
/// The backward recursion (22)-(23) in the plane, and the residual of each active element (24),
/// added to f.
template <class Scalar>
void planarElementResiduals(const Model& model, Workspace<Scalar>& ws, VectorX<Scalar>& f);

extern template void planarGeometry<double>(const Model&, Workspace<double>&, const VectorX<double>&, bool);
extern template void planarGeometry<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&, bool);
extern template void planarFrameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                              const VectorX<double>&, KinematicsLevel);
extern template void planarFrameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                                const VectorX<AdScalar>&, KinematicsLevel);
extern template void planarFrameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
extern template void planarFrameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&,
                                                              const VectorX<AdScalar>&);
extern template void planarBodyWrenches<double>(const Model&, Workspace<double>&, const Vector3<double>&, bool);
extern template void planarBodyWrenches<AdScalar>(const Model&, Workspace<AdScalar>&, const Vector3<AdScalar>&, bool);
extern template void planarElementResiduals<double>(const Model&, Workspace<double>&, VectorX<double>&);
extern template void planarElementResiduals<AdScalar>(const Model&, Workspace<AdScalar>&, VectorX<AdScalar>&);

}  // namespace mbsopt
