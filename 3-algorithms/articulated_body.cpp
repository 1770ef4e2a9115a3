#include "mbsopt/algorithms/articulated_body.hpp"

#include <cmath>

namespace mbsopt {

namespace {

using Vector6 = ArticulatedBodyFactorization::Vector6;
using Matrix6 = ArticulatedBodyFactorization::Matrix6;

Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& d) {
  Eigen::Matrix3d c;
  c << 0.0, -d.z(), d.y(), d.z(), 0.0, -d.x(), -d.y(), d.x(), 0.0;
  return c;
}

/// The spatial inertia of a rigid composite about its point (Featherstone (2.63) in ground axes):
/// [I  [h]×; [h]×ᵀ  m 1].
Matrix6 spatial(const CompositeInertia& rigid) {
  Matrix6 inertia;
  const Eigen::Matrix3d h = crossMatrix(rigid.first_moment);
  inertia << rigid.rotational, h, h.transpose(), rigid.mass * Eigen::Matrix3d::Identity();
  return inertia;
}

/// Adds Xᵀ A X to `target`: A, symmetric, taken about a point at d from target's point, shifted to
/// it. X maps a twist at target's point to one at A's, (ω, v) ↦ (ω, v + ω × d) = [1 0; D 1] with
/// D = −[d]× (2.21).
void addShifted(const Matrix6& A, const Eigen::Vector3d& d, Matrix6& target) {
  if (d.isZero(0.0)) {
    target += A;
    return;
  }
  const Eigen::Matrix3d D = -crossMatrix(d);
  const Eigen::Matrix3d lower_left = A.bottomLeftCorner<3, 3>() + A.bottomRightCorner<3, 3>() * D;
  const Eigen::Matrix3d cross_term = A.topRightCorner<3, 3>() * D;
  target.topLeftCorner<3, 3>() += A.topLeftCorner<3, 3>() + cross_term + cross_term.transpose() + D.transpose() * A.bottomRightCorner<3, 3>() * D;
  target.bottomLeftCorner<3, 3>() += lower_left;
  target.topRightCorner<3, 3>() += lower_left.transpose();
  target.bottomRightCorner<3, 3>() += A.bottomRightCorner<3, 3>();
}

}  // namespace

bool ArticulatedBodyFactorization::factor(const Model& model, const Workspace<double>& ws, const std::vector<int>& free) {
  const auto& elements = model.elements();
  // The nodes and the node that carries each frame, in the elements' topological order.
  slot_of_element_.assign(elements.size(), -1);
  for (std::size_t c = 0; c < free.size(); ++c)
    slot_of_element_[static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(free[c])].element)] = static_cast<int>(c);
  frame_node_.assign(static_cast<std::size_t>(model.frameCount()), -1);
  nodes_.clear();
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const int carrier = frame_node_[static_cast<std::size_t>(elements[k].entry)];
    const auto exit = static_cast<std::size_t>(elements[k].exit);
    if (slot_of_element_[k] < 0) {
      frame_node_[exit] = carrier;
      continue;
    }
    const Eigen::Vector3d parent_origin =
        carrier < 0 ? Eigen::Vector3d::Zero() : ws.position[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(carrier)].exit)];
    Node node;
    node.slot = slot_of_element_[k];
    node.parent = carrier;
    node.exit = static_cast<int>(exit);
    node.shift = ws.position[exit] - parent_origin;
    node.axis << ws.motion_angular[k], ws.motion_linear[k];
    frame_node_[exit] = static_cast<int>(nodes_.size());
    nodes_.push_back(node);
  }

  // The rigid composites: the bodies each node carries, then (backward) everything beyond it.
  composites_.assign(nodes_.size(), CompositeInertia{});
  for (const Body& body : model.bodies()) {
    const auto f = static_cast<std::size_t>(body.frame);
    const int i = frame_node_[f];
    if (i < 0) continue;  // carried by the ground
    addBody(model, body, ws.rotation[f], ws.position[f] - ws.position[static_cast<std::size_t>(nodes_[static_cast<std::size_t>(i)].exit)],
            composites_[static_cast<std::size_t>(i)]);
  }
  articulated_.resize(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) articulated_[i] = spatial(composites_[i]);

  // A joint's rotor inertia adds to its pivot D alone (JointArmature: a term of M's diagonal).
  rotor_.assign(free.size(), 0.0);
  for (const JointArmature& armature : model.armatures())
    if (const auto element = static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(armature.coordinate)].element);
        slot_of_element_[element] >= 0)
      rotor_[static_cast<std::size_t>(slot_of_element_[element])] = model.value(armature.inertia);

  bool definite = true;
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    Node& node = nodes_[i];
    if (node.parent >= 0) addShifted(composites_[i], node.shift, composites_[static_cast<std::size_t>(node.parent)]);
    node.U = articulated_[i] * node.axis;                                   // (7.37)
    const double pivot = node.axis.dot(node.U) + rotor_[static_cast<std::size_t>(node.slot)];  // D (7.38)
    const double locked = quadraticForm(composites_[i], node.axis.head<3>(), node.axis.tail<3>());
    if (!(pivot > kPivotRatio * locked && std::isfinite(pivot))) definite = false;
    node.inverse_pivot = 1.0 / pivot;
    if (node.parent < 0) continue;
    // I^A − U Uᵀ / D, the inertia the parent sees through the joint (7.39).
    articulated_[i].noalias() -= node.inverse_pivot * node.U * node.U.transpose();
    addShifted(articulated_[i], node.shift, articulated_[static_cast<std::size_t>(node.parent)]);
  }
  return definite;
}

void ArticulatedBodyFactorization::solve(const Eigen::VectorXd& tau, Eigen::VectorXd& x) const {
  const std::size_t n = nodes_.size();
  node_vectors_.assign(n, Vector6::Zero());
  u_.resize(static_cast<Eigen::Index>(n));
  x.resize(static_cast<Eigen::Index>(n));
  // Backward: the bias wrench p^A of every node about its exit origin (7.40), no velocity terms.
  for (std::size_t i = n; i-- > 0;) {
    const Node& node = nodes_[i];
    Vector6 p = node_vectors_[i];
    const double u = tau[node.slot] - node.axis.dot(p);
    u_[static_cast<Eigen::Index>(i)] = u;
    if (node.parent < 0) continue;
    p += (u * node.inverse_pivot) * node.U;
    Vector6& parent = node_vectors_[static_cast<std::size_t>(node.parent)];
    parent.head<3>() += p.head<3>() + node.shift.cross(p.tail<3>());  // the moment about the parent's origin
    parent.tail<3>() += p.tail<3>();
  }
  // Forward: the accelerations (7.41)-(7.42), from the ground's, zero; a parent's slot holds its
  // acceleration before any child reads it.
  for (std::size_t i = 0; i < n; ++i) {
    const Node& node = nodes_[i];
    Vector6 a = Vector6::Zero();
    if (node.parent >= 0) {
      const Vector6& a_parent = node_vectors_[static_cast<std::size_t>(node.parent)];
      a.head<3>() = a_parent.head<3>();
      a.tail<3>() = a_parent.tail<3>() - node.shift.cross(a_parent.head<3>());  // v + ω × d
    }
    const double rate = (u_[static_cast<Eigen::Index>(i)] - node.U.dot(a)) * node.inverse_pivot;
    x[node.slot] = rate;
    node_vectors_[i] = a + rate * node.axis;
  }
}

}  // namespace mbsopt
