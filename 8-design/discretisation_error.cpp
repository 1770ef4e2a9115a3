#include "mbsopt/design/discretisation_error.hpp"

#include <algorithm>
#include <cmath>

namespace mbsopt {

namespace {

/// log₂ of the ratio of two successive differences, clamped to [1, 4]; 4 where the second vanishes.
double observedOrder(double coarse, double fine) {
  if (!(std::abs(fine) > 0.0)) return 4.0;
  return std::clamp(std::log2(std::abs(coarse) / std::abs(fine)), 1.0, 4.0);
}

}  // namespace

bool DiscretisationError::canBeActive(Eigen::Index j) const {
  return constraint_values[j] + 2.0 * std::abs(constraint_errors[j]) >= 0.0;
}

double DiscretisationError::largestActiveConstraintError() const {
  double largest = 0.0;
  for (Eigen::Index j = 0; j < constraint_errors.size(); ++j)
    if (canBeActive(j)) largest = std::max(largest, std::abs(constraint_errors[j]));
  return largest;
}

double DiscretisationError::largestConstraintError() const {
  return constraint_errors.size() ? constraint_errors.cwiseAbs().maxCoeff() : 0.0;
}

double DiscretisationError::largest() const { return std::max(cost_error, largestActiveConstraintError()); }

GridValues gridValues(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                      const Eigen::VectorXd& x) {
  const DesignResponse response = evaluateDesign(problem, functionals, x);
  return {costFunctional(problem, response), response.constraints};
}

DiscretisationError discretisationError(const std::array<GridValues, 3>& values) {
  DiscretisationError out;
  out.cost = values[0].cost;
  // e_h = (ψ_h − ψ_{h/2}) / (1 − 2^{−p}), each value with the order its own differences show.
  const auto error = [](double coarse, double middle, double fine, double* order = nullptr) {
    const double p = observedOrder(coarse - middle, middle - fine);
    if (order) *order = p;
    return (coarse - middle) / (1.0 - std::pow(2.0, -p));
  };
  out.cost_error = std::abs(error(values[0].cost, values[1].cost, values[2].cost, &out.order));
  out.constraint_values = values[0].constraints;
  out.constraint_errors.resize(values[0].constraints.size());
  for (Eigen::Index j = 0; j < out.constraint_errors.size(); ++j)
    out.constraint_errors[j] = error(values[0].constraints[j], values[1].constraints[j], values[2].constraints[j]);
  return out;
}

}  // namespace mbsopt
