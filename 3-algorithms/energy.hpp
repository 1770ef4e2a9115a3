// Mechanical energy of a state: kinetic energy of the bodies, potential of gravity and of the
// springs of the force elements. Used by the energy sensor and as a self-check of conservative runs.
#pragma once

#include <Eigen/Core>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

/// The parts of the mechanical energy [J].
struct MechanicalEnergy {
  double kinetic = 0.0;  ///< Σ ½ m |v_c|² + ½ ωᵀ I_c ω over the bodies, + Σ ½ J q̇² of the joints' rotor inertias
  double gravity = 0.0;  ///< −Σ m g·r_c (zero at the ground origin)
  double springs = 0.0;  ///< ½k(q − r(t))², ½k(ℓ − ℓ₀)², ½kΔ² of the joint, point and track-guidance springs
  double potential() const { return gravity + springs; }
  double total() const { return kinetic + potential(); }
};

/// The energy of the state (q, q̇) at time t (t enters through a moving spring rest value r(t)).
/// Computes the frame kinematics at Velocity level into ws; allocates nothing.
MechanicalEnergy mechanicalEnergy(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& v, double t);

/// The same from the frame kinematics already in ws (forwardKinematics at Velocity level or above, at
/// (q, q̇)); q̇ for the joints' rotor inertias, ½ J q̇².
MechanicalEnergy mechanicalEnergyOfFrames(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& v, double t);

/// The part an energy sensor reports.
double energyPart(const MechanicalEnergy& energy, EnergyPart part);

}  // namespace mbsopt
