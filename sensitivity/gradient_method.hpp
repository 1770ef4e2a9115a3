// The gradient methods chosen by name (issue 4: "one interface, chosen by name"), for
// `mbsopt gradcheck` and for the optimizers' `--gradient` flag.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// adjoint, continuous-adjoint, direct, fd_forward, fd_central.
const std::vector<std::string>& gradientMethodNames();

/// Throws std::invalid_argument, listing the known names, unless `method` is one of them.
void requireGradientMethod(const std::string& method);

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
