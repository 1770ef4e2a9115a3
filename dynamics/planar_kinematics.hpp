// The rate stage of the forward recursion (20)-(21) for a planar model (Model::planar): every
// angular velocity and acceleration along z, every linear one in the xy plane. The cross products
// of the spatial recursion then reduce to ω × r = ω (−r_y, r_x) and ω × (ω × r) = −ω² (r_x, r_y),
// and the term ω_e × ω_rel vanishes: about a third of its products. The results are those of the
// spatial recursion, whose out-of-plane terms are exact zeros for such a model (0 · x), up to the
// order of the remaining operations. The out-of-plane components of the rates are not written:
// they keep the zeros a workspace starts with, which no other stage changes on a planar model.
#pragma once

#include "dynamics/kinematics.hpp"

namespace mbsopt {

/// frameRates (kinematics.hpp) for a planar model.
template <class Scalar>
void planarFrameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                      KinematicsLevel level);
/// frameAccelerationsAtRest (kinematics.hpp) for a planar model.
template <class Scalar>
void planarFrameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a);

extern template void planarFrameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                              const VectorX<double>&, KinematicsLevel);
extern template void planarFrameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                                const VectorX<AdScalar>&, KinematicsLevel);
extern template void planarFrameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
extern template void planarFrameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&,
                                                              const VectorX<AdScalar>&);

}  // namespace mbsopt
