#include "mbsopt/optimizers/optimizer.hpp"

#include <chrono>
#include <stdexcept>

#include "mbsopt/optimizers/auglag_lbfgs.hpp"
#include "mbsopt/optimizers/ipopt_optimizer.hpp"
#include "mbsopt/optimizers/nlopt_optimizer.hpp"
#include "mbsopt/optimizers/sdcc.hpp"

namespace mbsopt {

std::string toString(OptimizerStatus status) {
  switch (status) {
    case OptimizerStatus::Converged:
      return "converged";
    case OptimizerStatus::MaxIterations:
      return "max_iterations";
    case OptimizerStatus::Failed:
      return "failed";
    case OptimizerStatus::Unsupported:
      return "unsupported";
  }
  return "failed";
}

std::string toString(ReportedPoint point) {
  switch (point) {
    case ReportedPoint::Final:
      return "final";
    case ReportedPoint::CheapestFeasible:
      return "cheapest_feasible";
    case ReportedPoint::LeastInfeasible:
      return "least_infeasible";
  }
  return "cheapest_feasible";
}

namespace {

OptimizerResult sdcc(NlpProblem& problem, const OptimizerOptions& options) {
  return minimizeWithSdcc(problem, options, sdccSettings(options.settings));
}
OptimizerResult slsqp(NlpProblem& problem, const OptimizerOptions& options) {
  return minimizeWithNlopt({nlopt::LD_SLSQP}, problem, options);
}
OptimizerResult mma(NlpProblem& problem, const OptimizerOptions& options) {
  return minimizeWithNlopt({nlopt::LD_MMA}, problem, options);
}
OptimizerResult ccsaq(NlpProblem& problem, const OptimizerOptions& options) {
  return minimizeWithNlopt({nlopt::LD_CCSAQ}, problem, options);
}

}  // namespace

const std::vector<OptimizerInfo>& optimizers() {
  static const std::vector<OptimizerInfo> registry{
      {"sdcc", "the paper's steepest descent with constraint compensation (its equations (7)-(11))", true, false, true,
       &sdcc},
      {"slsqp", "NLopt's sequential quadratic programming with a BFGS Hessian (Kraft's SLSQP)", true, false, true,
       &slsqp},
      {"mma", "NLopt's method of moving asymptotes (Svanberg 2002); inequality constraints only", false, false, true,
       &mma},
      {"ccsaq", "NLopt's conservative convex separable quadratic approximations (Svanberg 2002); inequalities only",
       false, false, true, &ccsaq},
      {"ipopt", "Ipopt's interior-point method with a limited-memory quasi-Newton Hessian; its runs take turns", true,
       true, true, &minimizeWithIpopt},
      {"auglag_lbfgs", kAuglagLbfgsDescription, true, false, false, &minimizeWithAuglagLbfgs},
  };
  return registry;
}

std::vector<std::string> optimizerNames() {
  std::vector<std::string> names;
  for (const OptimizerInfo& info : optimizers()) names.push_back(info.name);
  return names;
}

std::vector<std::string> defaultComparisonOptimizers() {
  std::vector<std::string> names;
  for (const OptimizerInfo& info : optimizers())
    if (info.compared_by_default) names.push_back(info.name);
  return names;
}

const OptimizerInfo& optimizerInfo(const std::string& name) {
  for (const OptimizerInfo& info : optimizers())
    if (info.name == name) return info;
  std::string known;
  for (const OptimizerInfo& info : optimizers()) known += (known.empty() ? "" : ", ") + info.name;
  throw std::invalid_argument("unknown optimizer '" + name + "' (known: " + known + ")");
}

OptimizerResult minimize(const std::string& optimizer, NlpProblem& problem, const OptimizerOptions& options) {
  const OptimizerInfo& info = optimizerInfo(optimizer);
  if (problem.equalityCount() > 0 && !info.takes_equalities) {
    OptimizerResult result;
    result.optimizer = info.name;
    result.status = OptimizerStatus::Unsupported;
    result.message = info.name + " takes inequality constraints only; this problem has " +
                     std::to_string(problem.equalityCount()) + " equalities";
    return result;
  }
  const auto start_time = std::chrono::steady_clock::now();
  OptimizerResult result = info.run(problem, options);
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace mbsopt
