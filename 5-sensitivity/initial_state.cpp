#include "mbsopt/sensitivity/initial_state.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <string>
#include <vector>

#include "mbsopt/algorithms/assembly.hpp"
#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/algorithms/tangent.hpp"

namespace mbsopt {

namespace {

constexpr double kTolerance = 1e-12;  // what the scene's own assembly aims at (7-io/scene_file.cpp)

}  // namespace

bool designMovesLoopClosure(const DesignProblem& problem) {
  const Model& model = problem.scene.model;
  return std::any_of(problem.design.variables.begin(), problem.design.variables.end(), [&](const DesignVariable& v) {
    return movesLoopClosure(model, v.index);
  });
}

Eigen::MatrixXd closingDirections(const Scene& scene) {
  Workspace<double> ws(scene.model);
  Eigen::VectorXd b;
  Eigen::MatrixXd B;
  constraintJacobian(scene.model, ws, scene.q0, scene.model.freeCoordinates(), b, B);
  SvdPartition partition(scene.settings.svd_threshold);
  partition.setConstraintJacobian(B);
  return partition.constrainedDirections();
}

void designInitialState(const Scene& scene, const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  q = scene.q0;
  v = scene.v0;
  for (const int i : model.drivenCoordinates()) {  // the design's motion at t₀ = 0, as the integrator sets it
    q[i] = model.value(model.coordinates()[static_cast<std::size_t>(i)].motion, 0.0);
    v[i] = model.value(model.coordinates()[static_cast<std::size_t>(i)].motion, 0.0, 1);
  }
  if (model.constraintCount() == 0) return;
  const std::vector<int>& free = model.freeCoordinates();
  const Eigen::MatrixXd V1 = closingDirections(scene);
  Workspace<double> ws(model);
  Eigen::VectorXd b;
  Eigen::MatrixXd B;
  // Gauss-Newton on b(q₀ + V₁ z) = 0: B V₁ has full column rank, each step the least-squares one.
  closeLoops(model, ws, q, kTolerance,
             [&](const Eigen::VectorXd& b_now, const Eigen::MatrixXd& B_now, Eigen::VectorXd& step) {
               step = V1 * (B_now * V1).colPivHouseholderQr().solve(b_now);
             },
             b, B);
  // The scene's own assembly accepts 1e-9 where Gauss-Newton stagnates above its aim (assemble()).
  if (!(b.cwiseAbs().maxCoeff() <= std::max(kTolerance, 1e-9))) throwOpenLoops(model, b, "at this design ", "");
  // ḃ is linear in q̇: one least-squares step along V₁ closes it exactly (closeLoops left the
  // geometry at q in ws).
  frameRates(model, ws, v, v, KinematicsLevel::Velocity);
  closureEquations(model, ws, Derivative::Velocity, b);
  const Eigen::VectorXd step = V1 * (B * V1).colPivHouseholderQr().solve(b);
  for (std::size_t k = 0; k < free.size(); ++k) v[free[k]] -= step[static_cast<Eigen::Index>(k)];
}

}  // namespace mbsopt
