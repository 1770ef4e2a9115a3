// Forward recursion (paper §4.2): absolute position, velocity and acceleration of every frame from
// the joint coordinates, by the movement transformations (20)-(21) of each kinetostatic element.
#pragma once

#include "dynamics/model.hpp"
#include "dynamics/scalar.hpp"
#include "dynamics/workspace.hpp"

namespace mbsopt {

enum class KinematicsLevel { Position, Velocity, Acceleration };

/// Fills ws.rotation/position (and velocities, accelerations up to `level`) for all frames.
/// q, v, a hold every coordinate, driven ones included; v and a are read only when needed.
template <class Scalar>
void forwardKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                       const VectorX<Scalar>& v, const VectorX<Scalar>& a, KinematicsLevel level);

/// The rate stage of forwardKinematics alone: frame velocities (20)-(21) and, at Acceleration level,
/// accelerations for joint rates v and accelerations a, reusing the rotations, positions, joint
/// axes and biases already in ws (forwardKinematics at Velocity level or above, at the same q).
template <class Scalar>
void frameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                KinematicsLevel level);
/// The velocity recursion for the unit rate e_coordinate alone, into the frame rates (angular, linear):
/// into ws.angular_velocity/velocity it gives column `coordinate` of the velocity Jacobians. Skips
/// the elements before the coordinate's own, which it cannot move. Needs the rotations, positions
/// and joint axes in ws.
void unitRatePass(const Model& model, Workspace<double>& ws, int coordinate, std::vector<Eigen::Vector3d>& angular,
                  std::vector<Eigen::Vector3d>& linear);

extern template void frameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                        const VectorX<double>&, KinematicsLevel);
extern template void forwardKinematics<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                               const VectorX<double>&, const VectorX<double>&, KinematicsLevel);
extern template void forwardKinematics<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                                 const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                                 KinematicsLevel);

}  // namespace mbsopt
