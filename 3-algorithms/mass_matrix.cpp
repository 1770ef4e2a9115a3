#include "mbsopt/algorithms/mass_matrix.hpp"

#include "mbsopt/model/rigid_inertia.hpp"

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

/// The composite inertia of a planar model (Model::planar) about a frame's origin: what the planar
/// rows read of CompositeInertia, the mass, the first moment in the plane and the moment of inertia
/// about z (the parallel-axis shift of I_zz involves d in the plane alone, and a body's I_zz is the
/// same in every axes turned about z).
struct PlanarInertia {
  double mass = 0.0, hx = 0.0, hy = 0.0, izz = 0.0;
};

/// Force in the plane and moment about z at `point` (x, y), in ground axes.
struct PlanarWrench {
  double fx, fy, mz, px, py;
};

/// addShifted (rigid_inertia.hpp) in the plane: h += m d, I_zz += 2 u·d with u = h + m d / 2.
void addShifted(const PlanarInertia& beyond, double dx, double dy, PlanarInertia& composite) {
  composite.mass += beyond.mass;
  const double ux = beyond.hx + 0.5 * beyond.mass * dx, uy = beyond.hy + 0.5 * beyond.mass * dy;
  composite.hx += beyond.hx + beyond.mass * dx;
  composite.hy += beyond.hy + beyond.mass * dy;
  composite.izz += beyond.izz + 2.0 * (ux * dx + uy * dy);
}

void compositeInertias(const Model& model, const Workspace<double>& ws, std::vector<PlanarInertia>& composites) {
  composites.assign(static_cast<std::size_t>(model.frameCount()), PlanarInertia{});
  for (const Body& body : model.bodies()) {
    const auto f = static_cast<std::size_t>(body.frame);
    const Eigen::Vector3d c = ws.rotation[f] * model.centreOfMass(body);
    addShifted(PlanarInertia{model.value(body.mass), 0.0, 0.0, model.value(body.moments_of_inertia[2])}, c.x(), c.y(),
               composites[f]);
  }
  const auto& elements = model.elements();
  for (std::size_t k = elements.size(); k-- > 0;) {
    const auto e = static_cast<std::size_t>(elements[k].entry), s = static_cast<std::size_t>(elements[k].exit);
    addShifted(composites[s], ws.position[s].x() - ws.position[e].x(), ws.position[s].y() - ws.position[e].y(),
               composites[e]);
  }
}

/// unitAccelerationWrench below in the plane: f = m v̇ + ω̇ × h, n_z = I_zz ω̇ + (h × v̇)_z.
PlanarWrench unitAccelerationWrench(const PlanarInertia& composite, const Workspace<double>& ws, std::size_t k,
                                    std::size_t exit) {
  const double w = ws.motion_angular[k].z(), vx = ws.motion_linear[k].x(), vy = ws.motion_linear[k].y();
  return {composite.mass * vx - w * composite.hy, composite.mass * vy + w * composite.hx,
          composite.izz * w + composite.hx * vy - composite.hy * vx, ws.position[exit].x(), ws.position[exit].y()};
}

/// generalisedForce below in the plane.
double generalisedForce(const PlanarWrench& wrench, const Workspace<double>& ws, std::size_t k, std::size_t exit) {
  const double mz = wrench.mz + (wrench.px - ws.position[exit].x()) * wrench.fy -
                    (wrench.py - ws.position[exit].y()) * wrench.fx;
  return ws.motion_angular[k].z() * mz + ws.motion_linear[k].x() * wrench.fx + ws.motion_linear[k].y() * wrench.fy;
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

/// Column c of M (the joint of element i) and, by symmetry, row c: S_jᵀ IC_i S_i for the joints j
/// from element i to the ground (KinematicElement::parent_joint) whose coordinate is requested
/// (`position` ≥ 0).
template <class Inertia>
void fillColumnAndRow(const Model& model, const Workspace<double>& ws, const std::vector<Inertia>& composites,
                      const std::vector<int>& position, int i, Eigen::Index c, Eigen::MatrixXd& M) {
  const auto& elements = model.elements();
  const auto moved = static_cast<std::size_t>(elements[static_cast<std::size_t>(i)].exit);
  const auto wrench = unitAccelerationWrench(composites[moved], ws, static_cast<std::size_t>(i), moved);
  for (int j = i; j >= 0; j = elements[static_cast<std::size_t>(j)].parent_joint) {
    const KinematicElement& joint = elements[static_cast<std::size_t>(j)];
    const int r = position[static_cast<std::size_t>(joint.coordinate)];
    if (r >= 0)
      M(r, c) = M(c, r) = generalisedForce(wrench, ws, static_cast<std::size_t>(j), static_cast<std::size_t>(joint.exit));
  }
}

/// The mass matrix's block on `coordinates` from the composite inertias of type Inertia.
template <class Inertia>
void massMatrixBlock(const Model& model, Workspace<double>& ws, const std::vector<int>& coordinates, Eigen::MatrixXd& M) {
  thread_local std::vector<Inertia> composites;
  thread_local std::vector<int> position;  // of each coordinate in `coordinates`, or -1
  compositeInertias(model, ws, composites);
  subsetPositions(model, coordinates, position);
  const auto n = static_cast<Eigen::Index>(coordinates.size());
  M.setZero(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const int element = model.coordinates()[static_cast<std::size_t>(coordinates[static_cast<std::size_t>(c)])].element;
    fillColumnAndRow(model, ws, composites, position, element, c, M);
  }
  for (const JointArmature& armature : model.armatures())  // J on the diagonal, uncoupled
    if (const int r = position[static_cast<std::size_t>(armature.coordinate)]; r >= 0) M(r, r) += model.value(armature.inertia);
}

}  // namespace

// Composite Rigid Body Algorithm (Featherstone, Rigid Body Dynamics Algorithms, 2008, ch. 6). The joint of
// element i moves only what lies beyond it, so M(i, j) = S_jᵀ IC_i S_i for every joint j on the path
// from element i to the ground (i included), IC_i being the composite inertia beyond i, and
// M(i, j) = 0 when neither joint is on the other's path. One backward sweep for the IC, then one
// walk to the ground per requested column, from joint to joint. On a planar model the composites
// and the wrenches keep only their planar parts (PlanarInertia).
void massMatrix(const Model& model, Workspace<double>& ws, const std::vector<int>& coordinates, Eigen::MatrixXd& M) {
  if (model.planar()) massMatrixBlock<PlanarInertia>(model, ws, coordinates, M);
  else massMatrixBlock<CompositeInertia>(model, ws, coordinates, M);
}

void massMatrix(const Model& model, Workspace<double>& ws, Eigen::MatrixXd& M) {
  massMatrix(model, ws, allCoordinates(model), M);
}

}  // namespace mbsopt
