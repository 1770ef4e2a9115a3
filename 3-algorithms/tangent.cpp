#include "mbsopt/algorithms/tangent.hpp"

#include <algorithm>
#include <variant>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/residual.hpp"

namespace mbsopt {

void tangentMatrices(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double t, TangentMatrices& out) {
  const Eigen::Index n = model.coordinateCount();
  out.mass.resize(n, n);
  out.damping.resize(n, n);
  out.stiffness.resize(n, n);
  out.residual.resize(n);
  // Inputs ordered (q̈, q̇, q); passes of at most kMaxAdDirections seeded directions each.
  VectorX<AdScalar>& f = ws.seeded_f;
  for (Eigen::Index first = 0; first < 3 * n; first += kMaxAdDirections) {
    const Eigen::Index count = std::min<Eigen::Index>(kMaxAdDirections, 3 * n - first);
    seedVector(a, 0, first, count, ws.seeded_a);
    seedVector(v, n, first, count, ws.seeded_v);
    seedVector(q, 2 * n, first, count, ws.seeded_q);
    seedVector(lambda, 3 * n, first, count, ws.seeded_lambda);  // never seeded: constant
    residual(model, ws, ws.seeded_q, ws.seeded_v, ws.seeded_a, ws.seeded_lambda, t, f);
    for (Eigen::Index i = 0; i < n; ++i) {
      out.residual[i] = f[i].value();
      const AdDerivatives& d = f[i].derivatives();
      for (Eigen::Index j = 0; j < count; ++j) {
        const Eigen::Index input = first + j;
        const double value = d[j];
        if (input < n) out.mass(i, input) = value;
        else if (input < 2 * n) out.damping(i, input - n) = value;
        else out.stiffness(i, input - 2 * n) = value;
      }
    }
  }
}

void constraintJacobian(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                        const std::vector<int>& columns, Eigen::VectorXd& b, Eigen::MatrixXd& B) {
  B.resize(model.constraintCount(), static_cast<Eigen::Index>(columns.size()));
  thread_local Eigen::VectorXd column;
  frameGeometry(model, ws, q);  // rotations, positions, joint axes
  closureEquations(model, ws, Derivative::Position, b);
  // ḃ reads the rates of the frames the cuts join, and no other: per column, their unit-rate twists.
  const std::vector<Model::CutFramePath>& paths = model.cutFramePaths();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const auto element = static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(columns[c])].element);
    for (const Model::CutFramePath& path : paths) unitRateTwist(model, ws, columns[c], path.frame, path.on_path[element] != 0);
    closureEquations(model, ws, Derivative::Velocity, column);
    B.col(static_cast<Eigen::Index>(c)) = column;
  }
}

void constraintJacobian(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q, Eigen::VectorXd& b,
                        Eigen::MatrixXd& B) {
  constraintJacobian(model, ws, q, allCoordinates(model), b, B);
}

}  // namespace mbsopt
