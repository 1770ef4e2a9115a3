#include "mbsopt/integrators/run_checks.hpp"

#include <cmath>
#include <sstream>

#include "mbsopt/model/overloaded.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/integrators/newton_convergence.hpp"

namespace mbsopt {

bool conservesEnergy(const Model& model) {
  if (!model.drivenCoordinates().empty()) return false;
  for (const ForceElement& force : model.forces()) {
    const bool conservative = std::visit(
        Overloaded{[&](const JointSpringDamper& s) { return model.value(s.damping) == 0.0 && s.rest.isConstant(); },
                   [&](const PointSpringDamper& s) { return model.value(s.damping) == 0.0; },
                   [&](const RotationalDamper& d) { return model.value(d.damping) == 0.0; },
                   [](const JointActuation&) { return false; }, [](const TrackGuidance&) { return false; }},
        force);
    if (!conservative) return false;
  }
  return true;
}

StepDefect ClosureCheck::check(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& closure,
                               double tolerance) {
  frameReach(model, ws, reach_);
  double worst = 0.0, worst_value = 0.0;
  const CutJoint* where = nullptr;
  Eigen::Index row = 0;
  for (const CutJoint& cut : model.cuts()) {
    const int rows = equationCount(cut.kind);
    for (int k = 0; k < rows; ++k) {
      // A coincidence row relative to the reach of its frames (at least 1 m: a loop near the origin is
      // not held to a tighter absolute tolerance than 1 µm); an orthogonality row absolutely.
      const double scale = k < 3 ? std::max(1.0, closureRowScale(model, cut, k, reach_)) : 1.0;
      const double ratio = std::abs(closure[row + k]) / (tolerance * scale);
      if (!(ratio <= worst)) {  // NaN counts as the worst
        worst = ratio;
        worst_value = closure[row + k];
        where = &cut;
      }
    }
    row += rows;
  }
  if (worst <= 1.0) return {};
  std::ostringstream text;
  text << "the loops have come apart: closure error " << std::abs(worst_value) << " at cut '" << where->name
       << "', above the closure tolerance " << tolerance
       << " (the step is too large for this configuration, or Newton converged onto another branch)";
  return {text.str(), where->name, std::abs(worst_value)};
}

void EnergyWatch::start(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        double t, double tolerance) {
  active_ = conservesEnergy(model) && !model.bodies().empty();
  if (!active_) return;
  const MechanicalEnergy energy = mechanicalEnergy(model, ws, q, v, t);  // leaves the positions in ws
  double reach = 0.0, mass = 0.0;
  for (const Body& body : model.bodies()) {
    const auto k = static_cast<std::size_t>(body.frame);
    reach = std::max(reach, ws.position[k].norm() + model.centreOfMass(body).norm());
    mass += model.value(body.mass);
  }
  initial_ = energy.total();
  scale_ = energy.kinetic + std::abs(energy.springs) + 2.0 * mass * model.gravity().norm() * reach;
  tolerance_ = tolerance;
  active_ = scale_ > 0.0;
}

StepDefect EnergyWatch::check(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& v, double t) const {
  if (!active_) return {};
  const double growth = mechanicalEnergy(model, ws, q, v, t).total() - initial_;
  if (growth <= tolerance_ * scale_) return {};
  std::ostringstream text;
  text << "the mechanical energy grew by " << growth << " J (" << 100.0 * growth / scale_
       << " % of its scale " << scale_ << " J) although no force does work: the integration diverged "
       << "(take a smaller step)";
  return {text.str(), "", growth};
}

}  // namespace mbsopt
