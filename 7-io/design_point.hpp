// A design point as a user gives it, in SI units, checked as the scene file checks the same numbers:
// `mbsopt gradcheck --design`, `mbsopt precision --gradients --design`, `Problem.evaluate(design)`.
// The optimizers stay within the design's bounds, which loadDesignProblem checks the same way.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {

struct DesignPointRequest {
  std::vector<double> design;        ///< SI values of the design variables in the problem's order; empty: the scene's
  std::optional<double> artificial;  ///< b_{k+1} in the cost's units; empty: the problem's start
  /// Evaluate values outside the design's bounds too (the outputs then say which); values the scene
  /// itself refuses (a negative stiffness) stay refused.
  bool outside_bounds = false;
};

/// The request as the optimizers' scaled point x (initialPoint with the given values). An
/// std::invalid_argument naming the file when a value (b_{k+1}'s too) is missing, not finite, beyond
/// what its scale can represent, outside its bounds (unless allowed), or one that the scene file, loaded with it as `--set` loads it, refuses (at the
/// number's line, the scene's message, "(value from the design point PARAMETER=VALUE)").
Eigen::VectorXd checkedDesignPoint(const SceneSource& source, const std::vector<ParameterOverride>& overrides,
                                   const DesignProblem& problem, const DesignPointRequest& request);

/// "tmd.k = 1200 above its upper bound 1000", one per variable of x (b_{k+1} last) outside its bounds.
std::vector<std::string> outsideBounds(const DesignProblem& problem, const Eigen::VectorXd& x);

}  // namespace mbsopt
