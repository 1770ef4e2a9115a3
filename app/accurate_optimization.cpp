#include "app/accurate_optimization.hpp"

#include <cmath>
#include <cstdio>

namespace mbsopt {

namespace {

/// A grid is accepted at this fraction of the tolerance: the estimate is of an order that shows
/// itself only roughly on extremes over time (DiscretisationError::order).
constexpr double kGridMargin = 0.5;
/// The grid search at the start changes h by at most this many halvings or doublings.
constexpr int kMaxGridChanges = 6;

/// The problem on its grid refined by `halvings` (coarsened where negative: a fixed step only): the
/// step divided by 2^halvings, or every step of a time grid split into 2^halvings.
DesignProblem onGrid(DesignProblem problem, int halvings) {
  const auto refine = [halvings](NewmarkSettings& s) {
    if (s.time_grid) {
      for (int k = 0; k < halvings; ++k) s = halvedSteps(s);
    } else {
      s.step = std::ldexp(s.step, -halvings);
    }
  };
  refine(problem.scene.settings);
  for (LoadCase& c : problem.load_cases) refine(c.scene.settings);
  return problem;
}

/// The problem starting at the scaled point x: the design variables' values in its scene, b_{k+1}'s
/// start at x's last entry.
DesignProblem startingAt(DesignProblem problem, const Eigen::VectorXd& x) {
  for (std::size_t i = 0; i < problem.design.variables.size(); ++i) {
    const DesignVariable& v = problem.design.variables[i];
    const double value = x[static_cast<Eigen::Index>(i)] * v.scale;
    problem.scene.model.setParameter(v.parameter, value);
    for (LoadCase& c : problem.load_cases) c.scene.model.setParameter(v.parameter, value);
  }
  problem.design.artificial.initial = x[x.size() - 1] * problem.design.artificial.scale;
  return problem;
}

std::string describe(const DiscretisationError& e) {
  char text[200];
  std::snprintf(text, sizeof text, "h %s %g s: cost's functional %.8g, its discretisation error %.2g (order %.2g), "
                "largest of the constraints' %.2g",
                e.variable_steps ? "<=" : "=", e.step, e.cost, e.cost_error, e.order,
                e.constraint_errors.size() ? e.constraint_errors.cwiseAbs().maxCoeff() : 0.0);
  return text;
}

/// Halvings of h that bring `error`, falling at `order`, to the margin of the tolerance (at least one).
int halvingsFor(double error, double order, double tolerance) {
  return std::max(1, static_cast<int>(std::ceil(std::log2(error / (kGridMargin * tolerance)) / order)));
}

}  // namespace

AccurateOptimization optimizeToAccuracy(const DesignProblem& problem, const RunChoice& choice, double tolerance,
                                        const std::function<void(const IterationRecord&)>& on_iteration,
                                        const std::function<void(const std::string&)>& say) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw std::invalid_argument("--accuracy must be positive");
  if (extrapolationRuns(problem) > 1)
    throw std::invalid_argument("--accuracy chooses the grid of one Newmark run: take settings.integrator newmark");
  AccurateOptimization out;
  out.tolerance = tolerance;
  const DesignProblem formulated = formulatedProblem(problem, resolvedChoice(problem, choice));
  const std::vector<ConstraintFunctional> functionals = transcribe(formulated);
  // The first grid: halve the scene's steps until the estimate at the start is within the margin, or
  // double a fixed step while the next coarser grid would still be (a variable step sequence, the steps
  // an adaptive run chose at settings.local_tolerance, is only refined).
  const bool fixed_step = !problem.scene.settings.time_grid;
  int halvings = 0;
  bool refined = false;
  for (int change = 0; change < kMaxGridChanges; ++change) {
    const DesignProblem at = onGrid(formulated, halvings);
    out.grid_choice.push_back(discretisationError(at, functionals, initialPoint(at)));
    const DiscretisationError& e = out.grid_choice.back();
    say("grid at the start, " + describe(e));
    if (e.largest() > kGridMargin * tolerance) {
      halvings += halvingsFor(e.largest(), e.order, tolerance);
      refined = true;
    } else if (fixed_step && !refined && e.largest() * std::pow(2.0, e.order) <= kGridMargin * tolerance) {
      --halvings;
    } else {
      break;
    }
  }
  DesignProblem current = problem;
  for (int round = 0; round < kMaxAccuracyRounds; ++round) {
    const DesignProblem grid = onGrid(current, halvings);
    say("optimizing on the grid h " + std::string(fixed_step ? "= " : "<= ") +
        std::to_string(largestStep(grid.scene.settings)) + " s");
    out.rounds.push_back(runOptimization(grid, choice, on_iteration));
    const Eigen::VectorXd& x = out.rounds.back().result.x;
    out.at_optimum.push_back(discretisationError(onGrid(formulated, halvings), functionals, x));
    const DiscretisationError& e = out.at_optimum.back();
    say("at the optimum, " + describe(e));
    if (e.largest() <= tolerance) {
      out.met = true;
      break;
    }
    halvings += halvingsFor(e.largest(), e.order, tolerance);
    current = startingAt(current, x);
  }
  return out;
}

}  // namespace mbsopt
