// `mbsopt optimize --accuracy TOL` (docs/integrators.md §8): the optimizer runs on a fixed
// grid, so that the objective stays smooth in the design, chosen at the start so that the cost's and
// the constraints' discretisation errors are within the tolerance there and graded at the times the
// accelerations jump (4-integrators/track_breaks.hpp); at the optimum the errors are estimated again, and
// where they exceed it the grid is graded again (a break time moved) or refined and the optimizer
// continues from the optimum.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mbsopt/design/discretisation_error.hpp"
#include "mbsopt/design/optimization_run.hpp"

namespace mbsopt {

struct AccurateOptimization {
  double tolerance = 0.0;
  std::vector<DiscretisationError> grid_choice;  ///< the estimates at the start that chose the first grid
  std::vector<OptimizationRun> rounds;           ///< one optimizer run per grid, the last one the result
  std::vector<DiscretisationError> at_optimum;   ///< each round's estimate at its optimum
  bool met = false;  ///< the last estimate is within the tolerance
};

/// At most this many grids are tried in turn.
inline constexpr int kMaxAccuracyRounds = 4;

/// The choice a run driven by accuracy takes: `choice`, but where it names no formulation and the
/// problem's own is an integral of the violation (∫⟨φ⟩dt, ∫⟨φ⟩²dt, whose gradient vanishes where φ ≤ 0
/// and which an optimizer therefore meets only to its feasibility tolerance, a maximum exceeded by far
/// more than any tolerance asked of the discretisation: the tramway's yaw limit by 3.5e-4°, its cost
/// 4e-5 below the optimum), grid_max, which holds each maximum over the grid to its bound exactly
/// (docs/integrators.md §8). `why` is told when it does.
RunChoice accurateChoice(const DesignProblem& problem, RunChoice choice, std::string* why = nullptr);

/// The grid an estimate was made on: "h = 0.002 s", "h = 0.002 s, graded at 4 break times" or
/// "h <= 0.064 s" (a variable step sequence, its largest step).
std::string describeGrid(const DiscretisationError& e);

/// Optimizes `problem` with `choice` to `tolerance` (the cost's functional and each transcribed
/// constraint, in their own units). `say` is told of each grid chosen and each estimate.
AccurateOptimization optimizeToAccuracy(const DesignProblem& problem, const RunChoice& choice, double tolerance,
                                        const std::function<void(const IterationRecord&)>& on_iteration,
                                        const std::function<void(const std::string&)>& say);

}  // namespace mbsopt
