#include "app/discretisation_error.hpp"

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

double DiscretisationError::largest() const {
  return std::max(cost_error, constraint_errors.size() ? constraint_errors.cwiseAbs().maxCoeff() : 0.0);
}

DiscretisationError discretisationError(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                        const Eigen::VectorXd& x) {
  std::vector<double> costs;
  std::vector<Eigen::VectorXd> constraints;
  for (const int divisor : {1, 2, 4}) {
    DesignProblem grid = problem;
    grid.scene.settings.step /= divisor;
    for (LoadCase& c : grid.load_cases) c.scene.settings.step /= divisor;
    const DesignResponse response = evaluateDesign(grid, functionals, x);
    costs.push_back(costFunctional(grid, response));
    constraints.push_back(response.constraints);
  }
  DiscretisationError out;
  out.step = problem.scene.settings.step;
  out.cost = costs[0];
  out.order = observedOrder(costs[0] - costs[1], costs[1] - costs[2]);
  const double factor = 1.0 / (1.0 - std::pow(2.0, -out.order));
  out.cost_error = std::abs(costs[0] - costs[1]) * factor;
  out.constraint_errors = (constraints[0] - constraints[1]) * factor;
  return out;
}

}  // namespace mbsopt
