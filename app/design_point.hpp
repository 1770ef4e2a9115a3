// The point of a design problem a command works at: the scene's design, or the one given on the
// command line (`--design` in SI units, `--artificial` for b_{k+1}), in the optimizers' scaled variables.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "problems/scene_file.hpp"

namespace mbsopt {

/// initialPoint(problem) with the design variables replaced by `design` (SI, in the problem's order;
/// empty: keep the scene's) and b_{k+1} by `artificial` (in the cost's units). A SceneError naming the
/// scene when `design` has the wrong number of values.
Eigen::VectorXd designPoint(const SceneSource& source, const DesignProblem& problem, const std::vector<double>& design,
                            const std::optional<double>& artificial);

}  // namespace mbsopt
