#include "mbsopt/integrators/step_outcome.hpp"

#include <cmath>
#include <sstream>
#include <utility>

namespace mbsopt {

namespace {

std::string describe(const std::string& what, double time, long step, double residual_norm,
                     const std::string& element) {
  std::ostringstream out;
  out << what << " at t = " << time << " s (step " << step << ")";
  const bool residual = !std::isnan(residual_norm);
  if (residual) out << ", residual norm " << residual_norm;
  if (!element.empty()) out << (residual ? ", largest at '" : ", at '") << element << "'";
  return out.str();
}

}  // namespace

std::string toString(StepStatus status) {
  switch (status) {
    case StepStatus::Converged: return "converged";
    case StepStatus::StepTooLarge: return "step too large";
    case StepStatus::NewtonDiverged: return "Newton diverged";
    case StepStatus::LoopCannotClose: return "loop cannot close";
    case StepStatus::CheckFailed: return "check failed";
  }
  return "unknown";
}

SimulationError::SimulationError(const StepOutcome& outcome)
    : SimulationError(outcome.status, outcome.reason, outcome.time, outcome.step, outcome.residual_norm,
                      outcome.element) {}

SimulationError::SimulationError(StepStatus kind, const std::string& what, double t, long s, double norm,
                                 std::string where)
    : std::runtime_error(describe(what, t, s, norm, where)),
      status(kind),
      reason(what),
      time(t),
      step(s),
      residual_norm(norm),
      element(std::move(where)) {}

}  // namespace mbsopt
