// Residual of the equations of motion by forward then backward recursion (paper §4.2, (22)-(25),
// with the loop forces of (37)):  f(q̈, q̇, q, t) = M q̈ + h(q, q̇, t) − Q + Bᵀλ  for every coordinate.
#pragma once

#include <stdexcept>
#include <string>

#include "mbsopt/algorithms/kinematics.hpp"

namespace mbsopt {

/// q, v, a: all coordinates (driven ones included). lambda: constraintCount() multipliers (may be
/// empty when the model has no cut joint). f receives coordinateCount() rows.
template <class Scalar>
void residual(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, const VectorX<Scalar>& v,
              const VectorX<Scalar>& a, const VectorX<Scalar>& lambda, double t, VectorX<Scalar>& f);

/// What residual() does after its forward pass: the same residual with the kinematics of (q, q̇, q̈)
/// already in ws (forwardKinematics at Acceleration level, or frameRates on its geometry); q, q̇ and
/// q̈ are those of that state, for the force elements and the joints' rotor inertias.
template <class Scalar>
void residualFromKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                            const VectorX<Scalar>& v, const VectorX<Scalar>& a, const VectorX<Scalar>& lambda,
                            double t, VectorX<Scalar>& f);
/// M(q) q̈ + B(q)ᵀλ alone, with the kinematics of (q, 0, q̈) already in ws (frameAccelerationsAtRest
/// on its geometry; the frame velocities are taken to be zero and not read) and q̈ = `a` (for the
/// rotor inertias): the residual at q̇ = 0 without gravity and force elements, i.e.
/// f(q, 0, q̈, λ) − f(q, 0, 0, 0) (what a projection's correction q̈ = Δ with multipliers λ = μ adds
/// to f). lambda: constraintCount() multipliers.
template <class Scalar>
void inertialAndLoopForcesFromKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a,
                                         const VectorX<Scalar>& lambda, VectorX<Scalar>& f);
/// The geometry stage's results at q held by `from` (frameGeometry, or forwardKinematics at Velocity
/// level or beyond), with the bodies' axes R c and R I Rᵀ (computed in `from` if stale), as constants
/// of an AD pass in `to`: its rotations, positions, joint axes and biases, curve sliders' tracks and
/// body axes, with zero derivatives. For a pass that seeds neither q nor a model parameter, this
/// stands in for the geometry stage, whose AD arithmetic would only carry zeros; frameRates then
/// computes the rates on it. On a planar model only what changes with q is copied (the rotations'
/// xy block, the positions, the in-plane components of the joints' axes and biases, R c; not R I Rᵀ,
/// which the planar recursions do not read): the other entries are constants of the model that no
/// stage ever changes in any workspace of it (1 and 0 in the rotations, 0 out of the plane).
void constantGeometry(const Model& model, Workspace<double>& from, Workspace<AdScalar>& to);
/// The same constants in place: `ws` holds the geometry stage's results at q from an earlier pass
/// that seeded q or a parameter (forwardKinematics), and keeps their values with zero derivatives,
/// its body axes computed first if stale. A pass of velocities after one of positions at the same q
/// then needs no geometry in double.
void dropGeometryDerivatives(const Model& model, Workspace<AdScalar>& ws);
/// Whether the parameter p is the stiffness or the damping of a joint spring-damper, a point
/// spring-damper or a track guidance: f is then linear in it, through that element alone.
bool isLinearForceParameter(const Model& model, ParameterIndex p);
/// ∂f/∂p into `column` (coordinateCount() rows) when the parameter p enters f linearly through one
/// force element, as the stiffness or the damping of a joint spring-damper, a point spring-damper
/// or a track guidance; false (column untouched) for any other parameter. A joint spring-damper's
/// column is its one coordinate's term; for the others ws must hold the geometry and the frame
/// velocities of (q, q̇) (forwardKinematics at Velocity level or beyond, or frameRates on its
/// geometry), and its wrenches are overwritten. The exact derivative at the cost of at most one
/// backward pass in double, where a forward-AD pass would carry p as one more direction.
bool linearForceParameterColumn(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v, double t, ParameterIndex p, Eigen::VectorXd& column);
/// Whether linearForceParameterColumn reads ws for p: a linear force parameter that is not a joint
/// spring-damper's.
bool linearForceParameterReadsKinematics(const Model& model, ParameterIndex p);

extern template void residual<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                      const VectorX<double>&, const VectorX<double>&, const VectorX<double>&,
                                      double, VectorX<double>&);
extern template void residual<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&, double, VectorX<AdScalar>&);

}  // namespace mbsopt
