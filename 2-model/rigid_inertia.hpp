// The inertia of a rigid set of bodies about a point, in ground axes, and its parallel-axis shift:
// the composite inertias of the Composite Rigid Body Algorithm (mass_matrix.hpp) and the rigid
// parts of the articulated-body factorization (articulated_body.hpp).
#pragma once

#include <Eigen/Core>

#include "mbsopt/model/model.hpp"

namespace mbsopt {

/// Mass, first moment and rotational inertia about a point, in ground axes: for a point mass m at r
/// from it, first_moment = m r and rotational = m (|r|² 1 − r rᵀ).
struct CompositeInertia {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotational = Eigen::Matrix3d::Zero();
};

/// Adds `beyond`, taken about a point at offset d from the point of `composite`, to `composite`.
/// Parallel-axis theorem (every r becomes r + d): h += m d, and with u = h + m d / 2,
/// I += 2 (u·d) 1 − u dᵀ − d uᵀ (= 2 (h·d) 1 − h dᵀ − d hᵀ + m (|d|² 1 − d dᵀ)).
inline void addShifted(const CompositeInertia& beyond, const Eigen::Vector3d& d, CompositeInertia& composite) {
  composite.mass += beyond.mass;
  composite.first_moment += beyond.first_moment;
  composite.rotational += beyond.rotational;
  if (d.isZero(0.0)) return;  // same point: a revolute joint, a body centred on its frame
  const Eigen::Vector3d u = beyond.first_moment + 0.5 * beyond.mass * d;
  const Eigen::Matrix3d u_d = u * d.transpose();
  composite.first_moment += beyond.mass * d;
  composite.rotational -= u_d + u_d.transpose();
  composite.rotational.diagonal().array() += 2.0 * u.dot(d);
}

/// Adds a body whose frame has rotation R and lies at offset d from the point of `composite`: its
/// own inertia, in ground axes about its centre of mass, shifted there.
inline void addBody(const Model& model, const Body& body, const Eigen::Matrix3d& R, const Eigen::Vector3d& d,
                    CompositeInertia& composite) {
  const CompositeInertia about_centre{model.value(body.mass), Eigen::Vector3d::Zero(),
                                     R * model.inertia(body) * R.transpose()};
  addShifted(about_centre, d + R * model.centreOfMass(body), composite);
}

/// Sᵀ I S for the twist S = (ω, v) at the composite's point: twice the kinetic energy at that twist,
/// ω·(I ω) + 2 ω·(h × v) + m |v|².
inline double quadraticForm(const CompositeInertia& inertia, const Eigen::Vector3d& w, const Eigen::Vector3d& v) {
  return w.dot(inertia.rotational * w) + 2.0 * w.dot(inertia.first_moment.cross(v)) + inertia.mass * v.squaredNorm();
}

}  // namespace mbsopt
