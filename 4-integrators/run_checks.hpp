// The checks every Newmark step passes before a run goes on: a run that leaves them stops with an
// error (newmark.cpp throws a SimulationError with the time, the step and the element), so a run
// never returns a wrong answer silently.
//   - the state (q, q̇, q̈, λ) is finite;
//   - the loops are closed: every closure row within settings.closure_tolerance, a coincidence row
//     relative to the reach of its two frames (newton_convergence.hpp), an orthogonality row absolutely;
//   - where no force does work, the mechanical energy has not grown by more than
//     settings.energy_tolerance of its scale: the trapezoidal rule conserves it up to an O(h²)
//     oscillation, numerical damping and the projections only remove it, so growth means the step
//     diverged (for example onto another branch of a singular configuration).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/energy.hpp"

namespace mbsopt {

/// What a check found wrong; an empty reason means the step passed.
struct StepDefect {
  std::string reason;
  std::string element;  ///< the cut or coordinate it is largest at, if any
  double size = 0.0;
};

/// True when no force of the model does work: no damping, no actuation, no driven coordinate, no
/// track guidance and no spring whose rest value moves. Gravity and springs are conservative.
bool conservesEnergy(const Model& model);

/// Checks the loop closure; keeps its scratch buffers, so a check allocates nothing unless it fails.
class ClosureCheck {
 public:
  /// The largest closure row relative to its tolerance; a defect when above 1. ws must hold the
  /// positions at q; `closure` the position-level closure rows.
  StepDefect check(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& closure, double tolerance);

 private:
  std::vector<double> reach_;
};

/// Watches the mechanical energy of a conservative run.
class EnergyWatch {
 public:
  /// Starts watching at (q, v, t), or switches the watch off for a model that does not conserve energy.
  void start(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
             double tolerance);
  StepDefect check(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                   double t) const;
  bool active() const { return active_; }

 private:
  bool active_ = false;
  double initial_ = 0.0, scale_ = 0.0, tolerance_ = 0.0;
};

}  // namespace mbsopt
