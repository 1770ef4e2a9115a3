// `mbsopt optimize --accuracy TOL` (issue 18; docs/integrators.md §6): the optimizer runs on a fixed
// grid, so that the objective stays smooth in the design, chosen at the start so that the cost's and
// the constraints' discretisation errors are within the tolerance there; at the optimum the errors are
// estimated again, and where they exceed it the grid is refined and the optimizer continues from the
// optimum.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/discretisation_error.hpp"
#include "app/optimization_run.hpp"

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

/// Optimizes `problem` with `choice` to `tolerance` (the cost's functional and each transcribed
/// constraint, in their own units). `say` is told of each grid chosen and each estimate.
AccurateOptimization optimizeToAccuracy(const DesignProblem& problem, const RunChoice& choice, double tolerance,
                                        const std::function<void(const IterationRecord&)>& on_iteration,
                                        const std::function<void(const std::string&)>& say);

}  // namespace mbsopt
