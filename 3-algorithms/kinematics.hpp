// Forward recursion (paper §4.2): absolute position, velocity and acceleration of every frame from
// the joint coordinates, by the movement transformations (20)-(21) of each kinetostatic element.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/scalar.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

/// An element undefined in the current state: a point spring of zero length (the residual), a ball
/// joint turned beyond its chart (the geometry stage).
class DegenerateElementError : public std::domain_error {
 public:
  DegenerateElementError(std::string element, const std::string& what)
      : std::domain_error(what), element_(std::move(element)) {}
  const std::string& element() const { return element_; }

 private:
  std::string element_;
};

enum class KinematicsLevel { Position, Velocity, Acceleration };

/// Fills ws.rotation/position (and velocities, accelerations up to `level`) for all frames.
/// q, v, a hold every coordinate, driven ones included; v and a are read only when needed.
template <class Scalar>
void forwardKinematics(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                       const VectorX<Scalar>& v, const VectorX<Scalar>& a, KinematicsLevel level);

/// The geometric stage of forwardKinematics alone: rotations and positions of every frame, and the
/// joint axes and biases the rate stage (frameRates) and the Jacobians read; no frame rates.
template <class Scalar>
void frameGeometry(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q);

/// The rate stage of forwardKinematics alone: frame velocities (20)-(21) and, at Acceleration level,
/// accelerations for joint rates v and accelerations a, reusing the rotations, positions, joint
/// axes and biases already in ws (forwardKinematics at Velocity level or above, at the same q).
template <class Scalar>
void frameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                KinematicsLevel level);
/// frameRates at rest, q̇ = 0: every frame velocity zero, and the accelerations (20)-(21) of the joint
/// accelerations a alone, without the terms in q̇ (those of M(q) a). The same values as
/// frameRates(model, ws, 0, a, Acceleration), to the bit, at about a third of its products.
template <class Scalar>
void frameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a);
/// The spatial recursions behind frameRates and frameAccelerationsAtRest, for any model; those two
/// take the planar path (planar_recursions.hpp) on a model that is planar (Model::planar) and these
/// otherwise.
template <class Scalar>
void spatialFrameRates(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& v, const VectorX<Scalar>& a,
                       KinematicsLevel level);
template <class Scalar>
void spatialFrameAccelerationsAtRest(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& a);
/// Column `coordinate` of the velocity Jacobian of `frame`, into ws.angular_velocity[frame] and
/// ws.velocity[frame]: its rates when that coordinate alone moves, at unit rate. Every other element
/// is then rigid, so a frame the joint moves (`moved`: the joint is on its path from the ground)
/// moves with the joint's exit frame, transported rigidly, and any other frame rests. O(1); needs
/// the rotations, positions and joint axes in ws.
void unitRateTwist(const Model& model, Workspace<double>& ws, int coordinate, FrameIndex frame, bool moved);

extern template void spatialFrameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                               const VectorX<double>&, KinematicsLevel);
extern template void spatialFrameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                                 const VectorX<AdScalar>&, KinematicsLevel);
extern template void spatialFrameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
extern template void spatialFrameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&,
                                                               const VectorX<AdScalar>&);
extern template void frameRates<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                        const VectorX<double>&, KinematicsLevel);
extern template void frameRates<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                          const VectorX<AdScalar>&, KinematicsLevel);
extern template void frameAccelerationsAtRest<AdScalar>(const Model&, Workspace<AdScalar>&,
                                                        const VectorX<AdScalar>&);
extern template void frameAccelerationsAtRest<double>(const Model&, Workspace<double>&, const VectorX<double>&);
extern template void frameGeometry<double>(const Model&, Workspace<double>&, const VectorX<double>&);
extern template void forwardKinematics<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                               const VectorX<double>&, const VectorX<double>&, KinematicsLevel);
extern template void forwardKinematics<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                                 const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                                 KinematicsLevel);

}  // namespace mbsopt
