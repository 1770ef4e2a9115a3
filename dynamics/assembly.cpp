#include "dynamics/assembly.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "dynamics/closure.hpp"
#include "dynamics/svd_partition.hpp"
#include "dynamics/tangent.hpp"

namespace mbsopt {

AssemblyReport assemble(const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v, double t, double tolerance,
                        double svd_threshold) {
  AssemblyReport report;
  if (q.size() != model.coordinateCount() || v.size() != model.coordinateCount())
    throw std::invalid_argument("assemble: the state has " + std::to_string(q.size()) + " coordinates, the model " +
                                std::to_string(model.coordinateCount()));
  for (int i : model.drivenCoordinates()) {
    q[i] = model.coordinates()[static_cast<std::size_t>(i)].motion.value(t);
    v[i] = model.coordinates()[static_cast<std::size_t>(i)].motion.rate(t);
  }
  if (model.constraintCount() == 0) return report;
  const std::vector<int>& free = model.freeCoordinates();
  const auto nf = static_cast<Eigen::Index>(free.size());
  Workspace<double> ws(model);
  SvdPartition partition(svd_threshold);
  Eigen::VectorXd b, correction;
  Eigen::MatrixXd B_free;
  const Eigen::VectorXd q_start = q;
  auto factor = [&] {
    constraintJacobian(model, ws, q, free, b, B_free);
    partition.setConstraintJacobian(B_free);
  };
  constexpr int kMaxIterations = 50;
  factor();
  double best = b.cwiseAbs().maxCoeff();
  while (best > tolerance && report.iterations < kMaxIterations) {
    partition.pseudoInverse(b, correction);
    for (Eigen::Index k = 0; k < nf; ++k) q[free[static_cast<std::size_t>(k)]] -= correction[k];
    ++report.iterations;
    factor();
    const double now = b.cwiseAbs().maxCoeff();
    if (!std::isfinite(now)) break;
    if (now > 0.999 * best && report.iterations > 10) break;  // stagnates: not closable
    best = std::min(best, now);
  }
  report.closure_error = b.cwiseAbs().maxCoeff();
  if (!(report.closure_error <= std::max(tolerance, 1e-9))) {
    std::string names;
    std::vector<int> open;
    Eigen::Index row = 0;
    for (std::size_t c = 0; c < model.cuts().size(); ++c) {
      const int rows = equationCount(model.cuts()[c].kind);
      if (b.segment(row, rows).cwiseAbs().maxCoeff() > 1e-9) {
        names += (names.empty() ? "" : ", ") + model.cuts()[c].name;
        open.push_back(static_cast<int>(c));
      }
      row += rows;
    }
    throw AssemblyError("the loop(s) closed by " + names + " cannot be assembled: closure error " +
                            std::to_string(report.closure_error) + " m after " +
                            std::to_string(report.iterations) + " least-squares corrections",
                        std::move(open));
  }
  report.position_correction = (q - q_start).cwiseAbs().maxCoeff();
  checkWeldOrientations(model, ws);  // factor() left the geometry at q in ws
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
