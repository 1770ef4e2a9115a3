#include "mbsopt/algorithms/assembly.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/algorithms/tangent.hpp"

namespace mbsopt {

int closeLoops(const Model& model, Workspace<double>& ws, Eigen::VectorXd& q, double tolerance,
               const ClosureCorrection& correction, Eigen::VectorXd& b, Eigen::MatrixXd& B) {
  const std::vector<int>& free = model.freeCoordinates();
  constexpr int kMaxIterations = 50;
  constraintJacobian(model, ws, q, free, b, B);
  double best = b.cwiseAbs().maxCoeff();
  int iterations = 0;
  Eigen::VectorXd step;
  while (best > tolerance && iterations < kMaxIterations) {
    correction(b, B, step);
    for (std::size_t k = 0; k < free.size(); ++k) q[free[k]] -= step[static_cast<Eigen::Index>(k)];
    ++iterations;
    constraintJacobian(model, ws, q, free, b, B);
    const double now = b.cwiseAbs().maxCoeff();
    if (!std::isfinite(now)) break;
    if (now > 0.999 * best && iterations > 10) break;  // stagnates: not closable
    best = std::min(best, now);
  }
  return iterations;
}

void throwOpenLoops(const Model& model, const Eigen::VectorXd& b, const std::string& context, const std::string& detail) {
  std::string names;
  std::vector<int> open;
  Eigen::Index row = 0;
  for (std::size_t c = 0; c < model.cuts().size(); ++c) {
    const int rows = equationCount(model.cuts()[c].kind);
    if (!(b.segment(row, rows).cwiseAbs().maxCoeff() <= 1e-9)) {
      names += (names.empty() ? "" : ", ") + model.cuts()[c].name;
      open.push_back(static_cast<int>(c));
    }
    row += rows;
  }
  throw AssemblyError(context + "the loop(s) closed by " + names + " cannot be assembled: closure error " +
                          std::to_string(b.cwiseAbs().maxCoeff()) + " m" + detail,
                      std::move(open), b.cwiseAbs().maxCoeff());
}

AssemblyReport assemble(const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v, double t, double tolerance,
                        double svd_threshold) {
  AssemblyReport report;
  if (q.size() != model.coordinateCount() || v.size() != model.coordinateCount())
    throw std::invalid_argument("assemble: the state has " + std::to_string(q.size()) + " coordinates, the model " +
                                std::to_string(model.coordinateCount()));
  for (int i : model.drivenCoordinates()) {
    q[i] = model.value(model.coordinates()[static_cast<std::size_t>(i)].motion, t);
    v[i] = model.value(model.coordinates()[static_cast<std::size_t>(i)].motion, t, 1);
  }
  if (model.constraintCount() == 0) return report;
  const std::vector<int>& free = model.freeCoordinates();
  const auto nf = static_cast<Eigen::Index>(free.size());
  Workspace<double> ws(model);
  SvdPartition partition(svd_threshold);
  Eigen::VectorXd b, correction;
  Eigen::MatrixXd B_free;
  const Eigen::VectorXd q_start = q;
  // The minimum-norm correction B⁺b through the SVD of B, at each iterate.
  report.iterations = closeLoops(model, ws, q, tolerance,
                                 [&](const Eigen::VectorXd& b_now, const Eigen::MatrixXd& B_now, Eigen::VectorXd& step) {
                                   partition.setConstraintJacobian(B_now);
                                   partition.pseudoInverse(b_now, step);
                                 },
                                 b, B_free);
  report.closure_error = b.cwiseAbs().maxCoeff();
  if (!(report.closure_error <= std::max(tolerance, 1e-9)))
    throwOpenLoops(model, b, "", " after " + std::to_string(report.iterations) + " least-squares corrections");
  partition.setConstraintJacobian(B_free);  // at the final q, for the velocities
  report.position_correction = (q - q_start).cwiseAbs().maxCoeff();
  checkWeldOrientations(model, ws);  // closeLoops left the geometry at q in ws
  // Velocities: the minimum-norm correction onto ḃ = 0 in joint space, so the rates the user gave
  // change as little as possible (the integrator's own projections use the mass metric instead,
  // which removes the least kinetic energy; for a far-off input the two give different motions).
  frameRates(model, ws, v, v, KinematicsLevel::Velocity);
  closureEquations(model, ws, Derivative::Velocity, b);
  partition.pseudoInverse(b, correction);
  for (Eigen::Index k = 0; k < nf; ++k) v[free[static_cast<std::size_t>(k)]] -= correction[k];
  report.velocity_correction = correction.size() ? correction.cwiseAbs().maxCoeff() : 0.0;
  return report;
}

}  // namespace mbsopt
