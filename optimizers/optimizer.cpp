#include "mbsopt/optimizers/optimizer.hpp"

#include <chrono>
#include <stdexcept>

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

const std::vector<std::string>& optimizerNames() {
  static const std::vector<std::string> names{"sdcc", "slsqp", "mma", "ccsaq", "ipopt"};
  return names;
}

bool runsOneAtATime(const std::string& optimizer) { return optimizer == "ipopt"; }

namespace {

OptimizerResult dispatch(const std::string& optimizer, NlpProblem& problem, const OptimizerOptions& options) {
  if (optimizer == "sdcc") return minimizeWithSdcc(problem, options, sdccSettings(options.settings));
  if (optimizer == "slsqp") return minimizeWithNlopt(nlopt::LD_SLSQP, problem, options);
  if (optimizer == "mma") return minimizeWithNlopt(nlopt::LD_MMA, problem, options);
  if (optimizer == "ccsaq") return minimizeWithNlopt(nlopt::LD_CCSAQ, problem, options);
  if (optimizer == "ipopt") return minimizeWithIpopt(problem, options);
  std::string known;
  for (const std::string& name : optimizerNames()) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown optimizer '" + optimizer + "' (known: " + known + ")");
}

}  // namespace

OptimizerResult minimize(const std::string& optimizer, NlpProblem& problem, const OptimizerOptions& options) {
  const auto start_time = std::chrono::steady_clock::now();
  OptimizerResult result = dispatch(optimizer, problem, options);
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace mbsopt
