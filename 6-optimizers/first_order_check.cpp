#include "mbsopt/optimizers/first_order_check.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

namespace mbsopt {

namespace {

/// An active constraint's column of the least-squares system: where its multiplier goes, and its sign.
struct ActiveColumn {
  enum class Kind { Constraint, Lower, Upper } kind;
  Eigen::Index index;
  bool signed_multiplier;  ///< λ ≥ 0 (an inequality or a bound)
};

}  // namespace

FirstOrderCheck firstOrderCheck(const NlpProblem& problem, const Eigen::VectorXd& x, const NlpEvaluation& at,
                                double active_tolerance) {
  const Eigen::Index n = x.size(), inequalities = problem.inequalityCount();
  const Eigen::VectorXd lower = problem.lowerBounds(), upper = problem.upperBounds();
  FirstOrderCheck out;
  out.multipliers.constraints = Eigen::VectorXd::Zero(at.constraints.size());
  out.multipliers.lower = out.multipliers.upper = Eigen::VectorXd::Zero(n);
  // Derivatives per range of each variable: the test must not depend on the units the problem
  // chose for its variables (a cost that moves 1e-4 per kN is not stationary over a 950 kN range).
  // Scaling the rows leaves the multipliers those of the unscaled conditions.
  Eigen::VectorXd range(n);
  for (Eigen::Index j = 0; j < n; ++j)
    range[j] = std::isfinite(upper[j] - lower[j]) && upper[j] > lower[j] ? upper[j] - lower[j] : std::max(1.0, std::abs(x[j]));
  const Eigen::VectorXd cost_gradient = range.cwiseProduct(at.cost_gradient);
  const double scale = cost_gradient.cwiseAbs().maxCoeff();
  if (scale == 0.0) {
    out.residual = 0.0;
    return out;
  }
  std::vector<Eigen::VectorXd> columns;
  std::vector<ActiveColumn> active;
  for (Eigen::Index i = 0; i < at.constraints.size(); ++i) {
    const bool equality = i >= inequalities;
    if (equality || at.constraints[i] >= -active_tolerance) {
      columns.push_back(range.cwiseProduct(at.constraint_jacobian.row(i).transpose()));
      active.push_back({ActiveColumn::Kind::Constraint, i, !equality});
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const double reach = active_tolerance * range[j];
    if (x[j] - lower[j] <= reach) {  // l_j − x_j ≤ 0
      columns.push_back(-range[j] * Eigen::VectorXd::Unit(n, j));
      active.push_back({ActiveColumn::Kind::Lower, j, true});
    }
    if (upper[j] - x[j] <= reach) {  // x_j − u_j ≤ 0
      columns.push_back(range[j] * Eigen::VectorXd::Unit(n, j));
      active.push_back({ActiveColumn::Kind::Upper, j, true});
    }
  }
  // Least squares on the active set, dropping the most negative sign-constrained multiplier until
  // none is negative (each drop only removes a column, so the loop ends).
  std::vector<bool> kept(columns.size(), true);
  while (true) {
    std::vector<std::size_t> used;
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (kept[c]) used.push_back(c);
    if (used.empty()) return out;  // residual 1, no multipliers
    Eigen::MatrixXd A(n, static_cast<Eigen::Index>(used.size()));
    for (std::size_t k = 0; k < used.size(); ++k) A.col(static_cast<Eigen::Index>(k)) = columns[used[k]];
    const Eigen::VectorXd lambda = A.completeOrthogonalDecomposition().solve(-cost_gradient);
    Eigen::Index worst = -1;
    for (Eigen::Index k = 0; k < lambda.size(); ++k)
      if (active[used[static_cast<std::size_t>(k)]].signed_multiplier && lambda[k] < 0.0 &&
          (worst < 0 || lambda[k] < lambda[worst]))
        worst = k;
    if (worst >= 0) {
      kept[used[static_cast<std::size_t>(worst)]] = false;
      continue;
    }
    out.residual = (cost_gradient + A * lambda).cwiseAbs().maxCoeff() / scale;
    for (std::size_t k = 0; k < used.size(); ++k) {
      const ActiveColumn& column = active[used[k]];
      Eigen::VectorXd& target = column.kind == ActiveColumn::Kind::Constraint ? out.multipliers.constraints
                                : column.kind == ActiveColumn::Kind::Lower    ? out.multipliers.lower
                                                                              : out.multipliers.upper;
      target[column.index] = lambda[static_cast<Eigen::Index>(k)];
    }
    return out;
  }
}

}  // namespace mbsopt
