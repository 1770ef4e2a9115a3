#include "dynamics/mass_matrix.hpp"

#include "dynamics/rigid_inertia.hpp"

namespace mbsopt {

namespace {

/// Force and moment about `point`, all in ground axes.
struct Wrench {
  Eigen::Vector3d force;
  Eigen::Vector3d moment;
  Eigen::Vector3d point;
};

/// The composite inertia of every frame: the bodies on it and on every frame beyond it, about its
/// origin. One backward sweep: the elements are in topological order, so all the elements leaving
/// a frame come after the one entering it.
void compositeInertias(const Model& model, const Workspace<double>& ws, std::vector<CompositeInertia>& composites) {
  composites.assign(static_cast<std::size_t>(model.frameCount()), CompositeInertia{});
  for (const Body& body : model.bodies()) {
    const auto f = static_cast<std::size_t>(body.frame);
    addBody(model, body, ws.rotation[f], Eigen::Vector3d::Zero(), composites[f]);
  }
  const auto& elements = model.elements();
  for (std::size_t k = elements.size(); k-- > 0;) {
    const auto e = static_cast<std::size_t>(elements[k].entry), s = static_cast<std::size_t>(elements[k].exit);
    addShifted(composites[s], ws.position[s] - ws.position[e], composites[e]);
  }
}

/// IC S: the rate of momentum of the composite inertia IC of element k's exit frame when the joint
/// accelerates at unit rate from rest, S = (motion_angular, motion_linear):
/// f = m v̇ + ω̇ × h, n = I ω̇ + h × v̇ about the exit origin.
Wrench unitAccelerationWrench(const CompositeInertia& composite, const Workspace<double>& ws, std::size_t k,
                              std::size_t exit) {
  const Eigen::Vector3d& w = ws.motion_angular[k];
  const Eigen::Vector3d& v = ws.motion_linear[k];
  const Eigen::Vector3d& h = composite.first_moment;
  return {composite.mass * v + w.cross(h), composite.rotational * w + h.cross(v), ws.position[exit]};
}

/// Sᵀ w: the generalised force of a wrench on the joint of element k, whose axes S are taken at
/// its exit origin.
double generalisedForce(const Wrench& wrench, const Workspace<double>& ws, std::size_t k, std::size_t exit) {
  const Eigen::Vector3d moment = wrench.moment + (wrench.point - ws.position[exit]).cross(wrench.force);
  return ws.motion_angular[k].dot(moment) + ws.motion_linear[k].dot(wrench.force);
}

/// -1 for the coordinates not in `coordinates`, the position in it for the others.
void subsetPositions(const Model& model, const std::vector<int>& coordinates, std::vector<int>& position) {
  position.assign(static_cast<std::size_t>(model.coordinateCount()), -1);
  for (std::size_t c = 0; c < coordinates.size(); ++c)
    position[static_cast<std::size_t>(coordinates[c])] = static_cast<int>(c);
}

/// For every element, the nearest joint (active element) between it and the ground, not itself;
/// -1 when there is none. The elements are in topological order: a parent comes before its children.
void parentJoints(const Model& model, std::vector<int>& parent_joint) {
  const auto& elements = model.elements();
  parent_joint.resize(elements.size());
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const int parent = model.frames()[static_cast<std::size_t>(elements[k].entry)].element;
    parent_joint[k] = parent < 0 || elements[static_cast<std::size_t>(parent)].coordinate >= 0
                          ? parent
                          : parent_joint[static_cast<std::size_t>(parent)];
  }
}

/// Column c of M (the joint of element i) and, by symmetry, row c: S_jᵀ IC_i S_i for the joints j
/// from element i to the ground whose coordinate is requested (`position` ≥ 0).
void fillColumnAndRow(const Model& model, const Workspace<double>& ws, const std::vector<CompositeInertia>& composites,
                      const std::vector<int>& position, const std::vector<int>& parent_joint, int i, Eigen::Index c,
                      Eigen::MatrixXd& M) {
  const auto& elements = model.elements();
  const auto moved = static_cast<std::size_t>(elements[static_cast<std::size_t>(i)].exit);
  const Wrench wrench = unitAccelerationWrench(composites[moved], ws, static_cast<std::size_t>(i), moved);
  for (int j = i; j >= 0; j = parent_joint[static_cast<std::size_t>(j)]) {
    const KinematicElement& joint = elements[static_cast<std::size_t>(j)];
    const int r = position[static_cast<std::size_t>(joint.coordinate)];
    if (r >= 0)
      M(r, c) = M(c, r) = generalisedForce(wrench, ws, static_cast<std::size_t>(j), static_cast<std::size_t>(joint.exit));
  }
}

}  // namespace

// Composite Rigid Body Algorithm (Featherstone, Rigid Body Dynamics Algorithms, 2008, ch. 6). The joint of
// element i moves only what lies beyond it, so M(i, j) = S_jᵀ IC_i S_i for every joint j on the path
// from element i to the ground (i included), IC_i being the composite inertia beyond i, and
// M(i, j) = 0 when neither joint is on the other's path. One backward sweep for the IC, then one
// walk to the ground per requested column, from joint to joint.
void massMatrix(const Model& model, Workspace<double>& ws, const std::vector<int>& coordinates, Eigen::MatrixXd& M) {
  thread_local std::vector<CompositeInertia> composites;
  thread_local std::vector<int> position;  // of each coordinate in `coordinates`, or -1
  thread_local std::vector<int> parent_joint;
  compositeInertias(model, ws, composites);
  subsetPositions(model, coordinates, position);
  parentJoints(model, parent_joint);
  const auto n = static_cast<Eigen::Index>(coordinates.size());
  M.setZero(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const int element = model.coordinates()[static_cast<std::size_t>(coordinates[static_cast<std::size_t>(c)])].element;
    fillColumnAndRow(model, ws, composites, position, parent_joint, element, c, M);
  }
}

void massMatrix(const Model& model, Workspace<double>& ws, Eigen::MatrixXd& M) {
  massMatrix(model, ws, allCoordinates(model), M);
}

}  // namespace mbsopt
