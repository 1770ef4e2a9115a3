// What one step of an integrator came to (SUNDIALS' return flags, Drake's step outcome): converged,
// or why not, with the reason in words, when and where; and SimulationError, the exception that
// carries an outcome out of a run that cannot go on.
#pragma once

#include <limits>
#include <stdexcept>
#include <string>

namespace mbsopt {

enum class StepStatus {
  Converged,  ///< the step's equations are solved (attemptStep), its checks passed (acceptStep)
  /// The step led where the equations are undefined or singular (a non-finite residual, increment
  /// or state, a singular iteration matrix, an element whose force is undefined there), the loops
  /// came apart (Newton on another branch), or the energy grew where the scheme may only dissipate
  /// it: a smaller step may succeed.
  StepTooLarge,
  /// Newton did not converge from any of its starts: a smaller step may succeed.
  NewtonDiverged,
  /// No configuration at the step's time closes the loops (a link too short for a driven motion):
  /// no step size helps.
  LoopCannotClose,
  /// A check no step size is at fault for: a prescribed motion or an initial residual that is not
  /// finite.
  CheckFailed,
};

/// "converged", "step too large", "Newton diverged", "loop cannot close", "check failed".
std::string toString(StepStatus status);

/// Whether a smaller step may succeed where one with this status did not (what a step controller
/// retries).
inline bool smallerStepMayHelp(StepStatus status) {
  return status == StepStatus::StepTooLarge || status == StepStatus::NewtonDiverged;
}

struct StepOutcome {
  StepStatus status = StepStatus::Converged;
  std::string reason;   ///< what went wrong, in words ("" when converged)
  double time = 0.0;    ///< the time the step was to reach [s]
  long step = 0;        ///< the step's number
  double residual_norm = std::numeric_limits<double>::quiet_NaN();  ///< the last residual's ‖·‖∞ (NaN: none)
  std::string element;  ///< the element at fault, where one is ("" otherwise)
  bool converged() const { return status == StepStatus::Converged; }
};

/// A run that cannot go on: its what() says when, where and by how much.
class SimulationError : public std::runtime_error {
 public:
  explicit SimulationError(const StepOutcome& outcome);
  SimulationError(StepStatus status, const std::string& what, double time, long step, double residual_norm,
                  std::string element);
  StepOutcome outcome() const { return {status, reason, time, step, residual_norm, element}; }

  StepStatus status;
  std::string reason;  ///< what went wrong, without the time and the residual
  double time;
  long step;
  double residual_norm;
  std::string element;
};

}  // namespace mbsopt
