// The gradient methods by name (one registry), for `mbsopt gradcheck`, the optimizers' `--gradient`
// flag and every study: one interface whichever method computes the gradient.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// One gradient method in the registry (gradient_method.cpp).
struct GradientMethodInfo {
  std::string name;         ///< what --gradient, the records and the Python module call it
  std::string description;  ///< one sentence, for --help and the docs
  /// Differentiates one simulation: on a problem with load cases or extrapolation runs, each case's
  /// and each run's gradient is taken on its own simulation and combined as its values are. Finite
  /// differences instead difference the whole problem.
  bool differentiates_each_simulation = true;
  /// What one gradient costs in simulations per design variable where that is fixed (forward
  /// differences 1, central 2); 0 where it is measured (DesignNlp::measureGradientCost).
  int simulations_per_variable = 0;
  DesignGradient (*gradient)(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                             const Eigen::VectorXd& x, double fd_step, const DesignResponse* simulated,
                             int jobs) = nullptr;
};

/// adjoint, continuous-adjoint, direct, fd_forward, fd_central.
const std::vector<GradientMethodInfo>& gradientMethods();
/// The registered method `name`, or the one an alias names (fd: fd_central); std::invalid_argument
/// listing the names otherwise.
const GradientMethodInfo& gradientMethod(const std::string& name);
/// The registered names, in the registry's order.
std::vector<std::string> gradientMethodNames();
/// The names and the aliases: what a command line accepts.
std::vector<std::string> gradientMethodChoices();

/// The cost's and every constraint's gradient at the scaled point x by the named method;
/// `fd_step` is the finite differences' relative step. Throws std::invalid_argument for an unknown
/// name (the message lists the known ones) and where a method does not apply. `simulated`: the
/// simulation at x when the caller has it, so that no method simulates x again. `jobs`: threads
/// for the finite differences' simulations and for the step derivatives of adjoint and direct
/// (continuous-adjoint runs on one); the gradient does not depend on it.
DesignGradient designGradient(const std::string& method, const DesignProblem& problem,
                              const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                              double fd_step = 1e-6, const DesignResponse* simulated = nullptr, int jobs = 1);

}  // namespace mbsopt
