#include "mbsopt/optimizers/first_order_check.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

namespace mbsopt {

double firstOrderResidual(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& at,
                          double active_tolerance) {
  const Eigen::Index n = x.size(), inequalities = problem.inequalityCount();
  const Eigen::VectorXd lower = problem.lowerBounds(), upper = problem.upperBounds();
  // Derivatives per range of each variable: the test must not depend on the units the problem
  // chose for its variables (a cost that moves 1e-4 per kN is not stationary over a 950 kN range).
  Eigen::VectorXd range(n);
  for (Eigen::Index j = 0; j < n; ++j)
    range[j] = std::isfinite(upper[j] - lower[j]) && upper[j] > lower[j] ? upper[j] - lower[j] : std::max(1.0, std::abs(x[j]));
  const Eigen::VectorXd cost_gradient = range.cwiseProduct(at.cost_gradient);
  const double scale = cost_gradient.cwiseAbs().maxCoeff();
  if (scale == 0.0) return 0.0;
  // The active constraints' gradients as columns, and whether each multiplier must be ≥ 0.
  std::vector<Eigen::VectorXd> columns;
  std::vector<bool> signed_multiplier;
  for (Eigen::Index i = 0; i < at.constraints.size(); ++i) {
    const bool equality = i >= inequalities;
    if (equality || at.constraints[i] >= -active_tolerance) {
      columns.push_back(range.cwiseProduct(at.constraint_jacobian.row(i).transpose()));
      signed_multiplier.push_back(!equality);
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const double reach = active_tolerance * range[j];
    if (x[j] - lower[j] <= reach) columns.push_back(-Eigen::VectorXd::Unit(n, j));  // −x_j + l_j ≤ 0
    if (upper[j] - x[j] <= reach) columns.push_back(Eigen::VectorXd::Unit(n, j));   // x_j − u_j ≤ 0
    while (signed_multiplier.size() < columns.size()) signed_multiplier.push_back(true);
  }
  // Least squares on the active set, dropping the most negative sign-constrained multiplier until
  // none is negative (each drop only removes a column, so the loop ends).
  std::vector<bool> kept(columns.size(), true);
  while (true) {
    std::vector<std::size_t> used;
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (kept[c]) used.push_back(c);
    if (used.empty()) return 1.0;
    Eigen::MatrixXd A(n, static_cast<Eigen::Index>(used.size()));
    for (std::size_t k = 0; k < used.size(); ++k) A.col(static_cast<Eigen::Index>(k)) = columns[used[k]];
    const Eigen::VectorXd lambda = A.completeOrthogonalDecomposition().solve(-cost_gradient);
    Eigen::Index worst = -1;
    for (Eigen::Index k = 0; k < lambda.size(); ++k)
      if (signed_multiplier[used[static_cast<std::size_t>(k)]] && lambda[k] < 0.0 && (worst < 0 || lambda[k] < lambda[worst]))
        worst = k;
    if (worst < 0) return (cost_gradient + A * lambda).cwiseAbs().maxCoeff() / scale;
    kept[used[static_cast<std::size_t>(worst)]] = false;
  }
}

}  // namespace mbsopt
