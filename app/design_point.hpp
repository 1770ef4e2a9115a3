// The point of a design problem a command works at: the scene's design, or the one given on the
// command line (`--design` in SI units, `--artificial` for b_{k+1}), in the optimizers' scaled variables.
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "mbsopt/problems/scene_file.hpp"

namespace mbsopt {

/// `--design` and `--artificial` as typed.
struct DesignPointArgument {
  std::vector<double> design;        ///< SI values of the design variables, in the problem's order
  std::optional<double> artificial;  ///< b_{k+1} in the cost's units
};

/// Adds `--design` and `--artificial` to `command`; `condition` ("With --gradients: ", or empty)
/// starts their help. Returns the two options.
std::pair<CLI::Option*, CLI::Option*> addDesignPointOptions(CLI::App& command, DesignPointArgument& argument,
                                                            const std::string& condition = "");

/// initialPoint(problem) with the design variables replaced by `argument.design` (empty: keep the
/// scene's) and b_{k+1} by `argument.artificial`. A SceneError naming the scene when `design` has
/// the wrong number of values or a value is not finite.
Eigen::VectorXd designPoint(const SceneSource& source, const DesignProblem& problem, const DesignPointArgument& argument);

}  // namespace mbsopt
