#include "mbsopt/design/accurate_optimization.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <utility>

#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/integrators/track_breaks.hpp"

namespace mbsopt {

namespace {

/// A grid is accepted at this fraction of the tolerance: the estimate is of an order that shows
/// itself only roughly on extremes over time (DiscretisationError::order).
constexpr double kGridMargin = 0.5;
/// The grid search at the start changes h by at most this many halvings or doublings.
constexpr int kMaxGridChanges = 6;

/// Per scene of a problem (its own, then each load case's), the times at which its accelerations jump
/// (curvatureJumpTimes), read off a run at the design the scene holds on its own step.
struct BreakTimes {
  std::vector<double> scene;
  std::vector<std::vector<double>> load_cases;
  bool empty() const {
    bool none = scene.empty();
    for (const std::vector<double>& c : load_cases) none = none && c.empty();
    return none;
  }
};

std::vector<double> breakTimesOf(const Scene& scene) {
  if (!hasCurvatureJumps(scene.model)) return {};
  return curvatureJumpTimes(scene.model, NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0));
}

/// None where the problem runs on a time grid already (an adaptive run's steps, refined as they are).
BreakTimes breakTimesOf(const DesignProblem& problem) {
  if (problem.scene.settings.time_grid) return {};
  BreakTimes out{breakTimesOf(problem.scene), {}};
  for (const LoadCase& c : problem.load_cases) out.load_cases.push_back(breakTimesOf(c.scene));
  return out;
}

/// The largest distance between the break times of `a` and `b`; infinite where their counts differ.
double breakShift(const BreakTimes& a, const BreakTimes& b) {
  const auto shift = [](const std::vector<double>& x, const std::vector<double>& y) {
    if (x.size() != y.size()) return std::numeric_limits<double>::infinity();
    double largest = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) largest = std::max(largest, std::abs(x[i] - y[i]));
    return largest;
  };
  double largest = shift(a.scene, b.scene);
  for (std::size_t c = 0; c < a.load_cases.size(); ++c) largest = std::max(largest, shift(a.load_cases[c], b.load_cases[c]));
  return largest;
}

/// A grid of the procedure: the scene's step divided by 2^halvings (multiplied where negative: a
/// fixed step only) and graded at each scene's break times where it has any (gradedTimeGrid); or each
/// step of a time grid split into 2^halvings.
struct Grid {
  int halvings = 0;
  BreakTimes breaks;
};

/// The largest step of `settings` refined by `halvings` (coarsened where negative: a fixed step only):
/// each halving halves every step, a fixed one (the scene's uniformStep, which ends at the end time) and
/// those of a time grid alike.
double stepAfter(const NewmarkSettings& settings, int halvings) {
  return std::ldexp(settings.time_grid ? largestStep(settings) : uniformStep(settings), -halvings);
}

/// Whether the grid `halvings` from the scene's ends at the end time with a step exactly 2^−halvings
/// times the scene's: always when refined; coarsened, when the scene's steps pair up that often.
bool nestedGrid(const NewmarkSettings& settings, int halvings) {
  if (halvings >= 0) return true;
  if (settings.time_grid) return false;
  return stepsToCover(settings.end_time, settings.step) % (1L << -halvings) == 0;
}

/// The problem on `grid` (nestedGrid: every run ends at the end time).
DesignProblem onGrid(DesignProblem problem, const Grid& grid) {
  const auto place = [&](NewmarkSettings& s, const std::vector<double>& breaks) {
    if (s.time_grid) {
      for (int k = 0; k < grid.halvings; ++k) s = halvedSteps(s);
      return;
    }
    s.step = stepAfter(s, grid.halvings);
    if (!breaks.empty()) s.time_grid = gradedTimeGrid(s.step, s.end_time, breaks);
  };
  place(problem.scene.settings, grid.breaks.scene);
  for (std::size_t c = 0; c < problem.load_cases.size(); ++c)
    place(problem.load_cases[c].scene.settings, grid.breaks.load_cases.empty() ? std::vector<double>{} : grid.breaks.load_cases[c]);
  return problem;
}

/// The discretisation errors at one scaled point x of the problem on the grids of a procedure: each
/// grid's values with those of the grid refined once and twice, all ending at the end time.
/// Values already computed are kept, so that the grid search at the start, which doubles h, pays for one
/// new grid per estimate, not three.
class ErrorEstimates {
 public:
  ErrorEstimates(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                 Eigen::VectorXd x, BreakTimes breaks)
      : problem_(problem), functionals_(functionals), x_(std::move(x)), breaks_(std::move(breaks)) {}

  DiscretisationError at(int halvings) {
    const NewmarkSettings& s = problem_.scene.settings;
    const double step = stepAfter(s, halvings);
    std::array<GridValues, 3> values;
    for (int k = 0; k < 3; ++k) {
      auto found = values_.find(halvings + k);
      if (found == values_.end())
        found = values_.emplace(halvings + k, gridValues(onGrid(problem_, {halvings + k, breaks_}), functionals_, x_)).first;
      values[static_cast<std::size_t>(k)] = found->second;
    }
    DiscretisationError e = discretisationError(values);
    e.variable_steps = static_cast<bool>(s.time_grid);
    e.step = step;
    e.break_times = breaks_.scene;
    return e;
  }

 private:
  const DesignProblem& problem_;
  const std::vector<ConstraintFunctional>& functionals_;
  Eigen::VectorXd x_;
  BreakTimes breaks_;
  std::map<int, GridValues> values_;  ///< by halvings
};

/// The problem starting at the scaled point x: the design variables' values in its scene, b_{k+1}'s
/// start at x's last entry.
DesignProblem startingAt(DesignProblem problem, const Eigen::VectorXd& x) {
  for (std::size_t i = 0; i < problem.design.variables.size(); ++i) {
    const DesignVariable& v = problem.design.variables[i];
    const double value = x[static_cast<Eigen::Index>(i)] * v.scale;
    problem.scene.model.setParameter(v.index, value);
    for (LoadCase& c : problem.load_cases) c.scene.model.setParameter(v.index, value);
  }
  problem.design.artificial.initial = x[x.size() - 1] * problem.design.artificial.scale;
  return problem;
}

/// "h = 0.002 s", "h = 0.002 s, graded at 4 break times" or "h <= 0.064 s" (a variable step sequence's largest).
std::string describeGrid(double step, bool variable_steps, std::size_t break_times) {
  char text[120];
  if (variable_steps) std::snprintf(text, sizeof text, "h <= %g s", step);
  else if (break_times == 0) std::snprintf(text, sizeof text, "h = %g s", step);
  else std::snprintf(text, sizeof text, "h = %g s, graded at %zu break times", step, break_times);
  return text;
}

std::string describe(const DiscretisationError& e) {
  char text[200];
  std::snprintf(text, sizeof text, ": cost's functional %.8g, its discretisation error %.2g (order %.2g), "
                "largest of the constraints' %.2g (%.2g of those that can be active)",
                e.cost, e.cost_error, e.order, e.largestConstraintError(), e.largestActiveConstraintError());
  return describeGrid(e) + text;
}

/// Halvings of h that bring `error`, falling at `order`, to the margin of the tolerance (at least one).
int halvingsFor(double error, double order, double tolerance) {
  return std::max(1, static_cast<int>(std::ceil(std::log2(error / (kGridMargin * tolerance)) / order)));
}

}  // namespace

std::string describeGrid(const DiscretisationError& e) {
  return describeGrid(e.step, e.variable_steps, e.break_times.size());
}

RunChoice accurateChoice(const DesignProblem& problem, RunChoice choice, std::string* why) {
  const TimeMeasure own = problem.design.transcription.measure;
  if (!choice.formulation.empty() || (own != TimeMeasure::PositivePart && own != TimeMeasure::SquaredPositivePart))
    return choice;
  const std::string own_name = resolvedChoice(problem, RunChoice{}).formulation;
  choice.formulation = "grid_max";
  if (why)
    *why = "--accuracy transcribes each maximum over time as grid_max: the problem's own " + own_name +
           " is met only to the optimizer's feasibility tolerance, which moves the optimum by more than the "
           "discretisation (--formulation " + own_name + " keeps it)";
  return choice;
}

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
  // The first grid: from twice the scene's step (its estimate takes the runs at 2h, h and h/2), halve
  // it until the estimate at the start is within the margin, or double it while the next coarser grid
  // would still be, as long as the doubled steps still end at the end time (nestedGrid; a variable
  // step sequence, the steps an adaptive run chose at settings.local_tolerance, starts as it is and is
  // only refined). A fixed step is graded at the times the accelerations jump at the start
  // (gradedTimeGrid).
  const NewmarkSettings& scene = problem.scene.settings;
  const bool fixed_step = !scene.time_grid;
  Grid grid{nestedGrid(scene, -1) ? -1 : 0, breakTimesOf(formulated)};
  ErrorEstimates at_start(formulated, functionals, initialPoint(formulated), grid.breaks);
  bool refined = false;
  for (int change = 0; change < kMaxGridChanges; ++change) {
    out.grid_choice.push_back(at_start.at(grid.halvings));
    const DiscretisationError& e = out.grid_choice.back();
    say("grid at the start, " + describe(e));
    if (e.largest() > kGridMargin * tolerance) {
      grid.halvings += halvingsFor(e.largest(), e.order, tolerance);
      refined = true;
    } else if (nestedGrid(scene, grid.halvings - 1) && !refined &&
               e.largest() * std::pow(2.0, e.order) <= kGridMargin * tolerance) {
      --grid.halvings;
    } else {
      break;
    }
  }
  DesignProblem current = problem;
  for (int round = 0; round < kMaxAccuracyRounds; ++round) {
    const DesignProblem on_grid = onGrid(current, grid);
    say("optimizing on the grid " +
        describeGrid(stepAfter(problem.scene.settings, grid.halvings), !fixed_step, grid.breaks.scene.size()));
    out.rounds.push_back(runOptimization(on_grid, choice, on_iteration));
    const Eigen::VectorXd& x = out.rounds.back().result.x;
    out.at_optimum.push_back(ErrorEstimates(formulated, functionals, x, grid.breaks).at(grid.halvings));
    const DiscretisationError& e = out.at_optimum.back();
    say("at the optimum, " + describe(e));
    if (e.largest() <= tolerance) {
      out.met = true;
      break;
    }
    current = startingAt(current, x);
    // Where the design moved a break time out of the step that crosses it, that crossing is first
    // order again: the grid is graded at the optimum's break times before it is refined.
    const BreakTimes moved = grid.breaks.empty() ? BreakTimes{} : breakTimesOf(current);
    const double shift = grid.breaks.empty() ? 0.0 : breakShift(grid.breaks, moved);
    if (shift > crossingStep(stepAfter(problem.scene.settings, grid.halvings), problem.scene.settings.end_time)) {
      char text[160];
      std::snprintf(text, sizeof text, "the break times moved with the design (by up to %.2g s): the grid graded again "
                    "at the optimum's", shift);
      say(text);
      grid.breaks = moved;
    } else {
      grid.halvings += halvingsFor(e.largest(), e.order, tolerance);
    }
  }
  return out;
}

}  // namespace mbsopt
