#include "app/discretisation_error.hpp"

#include <algorithm>
#include <cmath>

#include "mbsopt/dynamics/extrapolation.hpp"

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
  // Every grid ends where h's does (the first multiple of h at or after the end time; a time grid's end).
  const auto end = [](NewmarkSettings& s) {
    if (!s.time_grid) s.end_time = static_cast<double>(stepsToCover(s.end_time, s.step)) * s.step;
  };
  DesignProblem grid = problem;
  end(grid.scene.settings);
  for (LoadCase& c : grid.load_cases) end(c.scene.settings);
  for (int halvings = 0; halvings < 3; ++halvings) {
    if (halvings > 0) {
      grid.scene.settings = halvedSteps(grid.scene.settings);
      for (LoadCase& c : grid.load_cases) c.scene.settings = halvedSteps(c.scene.settings);
    }
    const DesignResponse response = evaluateDesign(grid, functionals, x);
    costs.push_back(costFunctional(grid, response));
    constraints.push_back(response.constraints);
  }
  DiscretisationError out;
  out.step = largestStep(problem.scene.settings);
  out.variable_steps = static_cast<bool>(problem.scene.settings.time_grid);
  out.cost = costs[0];
  // e_h = (ψ_h − ψ_{h/2}) / (1 − 2^{−p}), each value with the order its own differences show.
  const auto error = [](double coarse, double middle, double fine, double* order = nullptr) {
    const double p = observedOrder(coarse - middle, middle - fine);
    if (order) *order = p;
    return (coarse - middle) / (1.0 - std::pow(2.0, -p));
  };
  out.cost_error = std::abs(error(costs[0], costs[1], costs[2], &out.order));
  out.constraint_errors.resize(constraints[0].size());
  for (Eigen::Index j = 0; j < constraints[0].size(); ++j)
    out.constraint_errors[j] = error(constraints[0][j], constraints[1][j], constraints[2][j]);
  return out;
}

}  // namespace mbsopt
