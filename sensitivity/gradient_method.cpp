#include "sensitivity/gradient_method.hpp"

#include <algorithm>
#include <stdexcept>

#include "sensitivity/continuous_adjoint.hpp"
#include "sensitivity/direct_sensitivity.hpp"
#include "sensitivity/discrete_adjoint.hpp"

namespace mbsopt {

const std::vector<std::string>& gradientMethodNames() {
  static const std::vector<std::string> names{"adjoint", "continuous-adjoint", "direct", "fd_forward", "fd_central"};
  return names;
}

DesignGradient designGradient(const std::string& method, const DesignProblem& problem,
                              const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                              double fd_step, const DesignResponse* simulated, int jobs) {
  if (method == "adjoint") return adjointGradient(problem, functionals, x, simulated, jobs);
  if (method == "continuous-adjoint") return continuousAdjointGradient(problem, functionals, x, simulated);
  if (method == "direct") return directGradient(problem, functionals, x, simulated, jobs);
  if (method == "fd_forward") return finiteDifferenceGradient(problem, functionals, x, fd_step, false, simulated, jobs);
  requireGradientMethod(method);
  return finiteDifferenceGradient(problem, functionals, x, fd_step, true, simulated, jobs);  // fd_central
}

void requireGradientMethod(const std::string& method) {
  const auto& names = gradientMethodNames();
  if (std::find(names.begin(), names.end(), method) != names.end()) return;
  std::string known;
  for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown gradient method '" + method + "' (known: " + known + ")");
}

}  // namespace mbsopt
