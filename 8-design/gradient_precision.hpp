// The work-precision study of design gradients (`mbsopt precision SCENE --gradients`): each
// gradient method at several steps h, against a reference gradient (the direct method at a tiny step).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/design/precision_run.hpp"

namespace mbsopt {

struct GradientReference {
  std::string method = "direct";
  double step = 0.0;     ///< [s]
  double seconds = 0.0;  ///< its wall time
  std::vector<std::string> functionals;  ///< "cost", then every transcribed constraint, the rows of `gradient`
  DesignGradient gradient;
};

/// The gradient of every functional at the scaled point x by the direct method at `step`.
GradientReference referenceGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                    const Eigen::VectorXd& x, double step);

/// Whether any functional's reference gradient depends on the design variables (the artificial
/// variable's column aside): at a point where every constraint is inactive they are all zero, and a
/// comparison of methods says nothing.
bool dependsOnDesign(const GradientReference& reference);

/// One method at one step, timed over `repeat` runs: the relative error of each functional's gradient
/// in the design variables (relativeDifference) against the reference, the run's error their largest.
/// The column of b_{k+1} is left out: it is exact and the same for every method (artificialColumn),
/// and would otherwise hide the differences between them. A SimulationError, or a
/// method that does not apply (std::invalid_argument), makes it a failed run with the message.
PrecisionRun measureGradientRun(DesignProblem problem, const std::vector<ConstraintFunctional>& functionals,
                                const Eigen::VectorXd& x, const std::string& method, double step, double fd_step,
                                const GradientReference& reference, int repeat);

}  // namespace mbsopt
