#include "sensitivity/initial_state.hpp"

#include <Eigen/QR>
#include <cmath>
#include <string>
#include <vector>

#include "dynamics/assembly.hpp"
#include "dynamics/closure.hpp"
#include "dynamics/svd_partition.hpp"
#include "dynamics/tangent.hpp"

namespace mbsopt {

namespace {

constexpr double kTolerance = 1e-12;  // the scene's own assembly's (problems/scene_file.cpp)
constexpr int kMaxIterations = 50;

/// q[free] += V₁ step.
void moveAlong(const std::vector<int>& free, const Eigen::MatrixXd& directions, const Eigen::VectorXd& step,
               Eigen::VectorXd& x) {
  const Eigen::VectorXd change = directions * step;
  for (std::size_t k = 0; k < free.size(); ++k) x[free[k]] += change[static_cast<Eigen::Index>(k)];
}

}  // namespace

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
  if (model.constraintCount() == 0) return;
  const std::vector<int>& free = model.freeCoordinates();
  Workspace<double> ws(model);
  Eigen::VectorXd b;
  Eigen::MatrixXd B;
  constraintJacobian(model, ws, q, free, b, B);
  if (!(b.cwiseAbs().maxCoeff() > kTolerance)) return;  // closed: the scene's state (NaN goes on, and fails below)
  const Eigen::MatrixXd V1 = closingDirections(scene);
  // Gauss-Newton on b(q₀ + V₁ z) = 0: B V₁ has full column rank, each step the least-squares one.
  double error = b.cwiseAbs().maxCoeff();
  for (int iteration = 0; iteration < kMaxIterations && error > kTolerance; ++iteration) {
    moveAlong(free, V1, (B * V1).colPivHouseholderQr().solve(-b), q);
    constraintJacobian(model, ws, q, free, b, B);
    const double now = b.cwiseAbs().maxCoeff();
    if (!std::isfinite(now) || (iteration > 10 && now > 0.999 * error)) {  // diverges or stagnates
      error = now;
      break;
    }
    error = now;
  }
  if (!(error <= kTolerance)) {
    std::vector<int> open;
    std::string names;
    Eigen::Index row = 0;
    for (std::size_t c = 0; c < model.cuts().size(); ++c) {
      const int rows = equationCount(model.cuts()[c].kind);
      if (!(b.segment(row, rows).cwiseAbs().maxCoeff() <= kTolerance)) {
        names += (names.empty() ? "'" : ", '") + model.cuts()[c].name + "'";
        open.push_back(static_cast<int>(c));
      }
      row += rows;
    }
    throw AssemblyError("at this design the loop(s) closed by " + names +
                            " cannot be assembled: closure error " + std::to_string(error) + " m",
                        std::move(open));
  }
  // ḃ is linear in q̇: one least-squares step along V₁ closes it exactly (constraintJacobian left
  // the geometry at q in ws).
  frameRates(model, ws, v, v, KinematicsLevel::Velocity);
  closureEquations(model, ws, Derivative::Velocity, b);
  moveAlong(free, V1, (B * V1).colPivHouseholderQr().solve(-b), v);
}

}  // namespace mbsopt
