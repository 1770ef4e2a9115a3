// x = M⁻¹ τ without forming M: the articulated-body factorization of the mass matrix (Featherstone,
// "Rigid Body Dynamics Algorithms", 2008, §7.3: the articulated-body algorithm with zero velocities
// and no applied forces), O(n) per factorization and per solve on any tree of elements, where the
// dense path forms M in O(n²) and factors it in O(n³). The Newmark step uses it on large models for
// its projections and for Newton with J = M (SvdPartition's range-space solve). M is the block on
// the free coordinates: driven coordinates are locked (their acceleration is given).
//
// The tree is taken joint by joint: one node per free coordinate, whose parent is the nearest free
// joint between it and the ground. What lies between two nodes (offsets, locked joints, the bodies
// on their frames) moves rigidly with the inner one, so it only shifts spatial quantities, and in
// ground axes a shift is a translation. Spatial quantities are in ground axes about each node's
// exit origin: twists (ω, v), wrenches (moment, force), inertias 6 × 6 in that order. Node i with
// joint axes S (at its exit origin): U = I^A S, D = Sᵀ U, and its parent sees I^A − U Uᵀ / D
// (7.37)-(7.39), shifted to the parent's origin.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/rigid_inertia.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

class ArticulatedBodyFactorization {
 public:
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  /// A pivot D below this fraction of the inertia the same joint sees with every joint beyond it
  /// locked (Sᵀ I^C S, M's diagonal entry) makes M nearly singular in that joint's direction: the
  /// solves could lose up to as many digits, so factor() declines and the caller takes a dense path.
  static constexpr double kPivotRatio = 1e-6;

  /// Factorises M on the coordinates `free` (distinct; the solves' vectors are in that order) at
  /// the geometry in ws (rotations, positions and joint axes at q: forwardKinematics at Velocity
  /// level or above). Returns false when a pivot is not positive and finite or below kPivotRatio
  /// of its diagonal entry; the solves are then undefined.
  bool factor(const Model& model, const Workspace<double>& ws, const std::vector<int>& free);
  /// x = M⁻¹ τ (7.40)-(7.42) with zero velocities: one backward sweep of wrenches, one forward sweep
  /// of accelerations. x may not alias tau.
  void solve(const Eigen::VectorXd& tau, Eigen::VectorXd& x) const;

  /// The number of free coordinates of the last factor().
  Eigen::Index size() const { return static_cast<Eigen::Index>(nodes_.size()); }

 private:
  struct Node {
    int slot;               ///< position of its coordinate in `free`
    int parent;             ///< the parent node, or -1 when it hangs from the ground
    int exit;               ///< its exit frame
    Eigen::Vector3d shift;  ///< its exit origin − its parent's (or the ground's origin)
    Vector6 axis;           ///< S at the exit origin
    Vector6 U;              ///< I^A S
    double inverse_pivot;   ///< 1 / D
  };
  std::vector<Node> nodes_;  ///< in topological order
  // Buffers of factor(), kept so that it allocates nothing once sized.
  std::vector<int> slot_of_element_;  ///< per element: its coordinate's slot in `free`, or -1
  std::vector<double> rotor_;         ///< per slot: its joint's rotor inertia (JointArmature), 0 without
  std::vector<int> frame_node_;       ///< per frame: the node that carries it rigidly, -1 for the ground's
  std::vector<CompositeInertia> composites_;  ///< per node: I^C, every body beyond its joint, rigid
  std::vector<Matrix6> articulated_;          ///< per node: I^A
  mutable std::vector<Vector6> node_vectors_;  ///< per node: bias wrenches, then accelerations
  mutable Eigen::VectorXd u_;                  ///< per node: τ − Sᵀ p^A (7.40)
};

}  // namespace mbsopt
