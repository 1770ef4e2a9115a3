#include "mbsopt/design/bound_worth.hpp"

#include <cmath>

#include "mbsopt/model/units.hpp"
#include "mbsopt/design/constraint_verdicts.hpp"

namespace mbsopt {

double BoundWorth::relaxingLowersCostBy() const {
  if (equality) return derivative;
  return raising_relaxes ? -derivative : derivative;
}

std::vector<BoundWorth> boundWorth(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                   const DesignResponse& response, const FirstOrderMultipliers& multipliers) {
  const Model& model = problem.scene.model;
  const Sensor& cost_sensor = model.sensors()[static_cast<std::size_t>(sensorIndex(model, problem.design.cost.sensor))];
  const double cost_unit = inUnits(cost_sensor, 1.0);  // SI → the cost's reported unit
  std::vector<BoundWorth> out;
  // dΨ*/dB_i = Σ_j λ_j ∂g_j/∂B_i (the envelope theorem on the Lagrangian f + Σ λ_j g_j).
  const Eigen::VectorXd derivatives = boundJacobian(problem, functionals, response).transpose() * multipliers.constraints;
  for (std::size_t i = 0; i < problem.design.constraints.size(); ++i) {
    const double d = derivatives[static_cast<Eigen::Index>(i)];
    if (d == 0.0) continue;
    const ResponseConstraint& c = problem.design.constraints[i];
    const Sensor& sensor = model.sensors()[static_cast<std::size_t>(sensorIndex(model, c.sensor))];
    const double unit = inUnits(sensor, 1.0);
    BoundWorth w;
    w.kind = BoundWorth::Kind::Constraint;
    w.name = constraintName(c);
    w.index = static_cast<int>(i);
    w.unit = measureUnit(model, sensor, c.of);
    w.bound = c.bound * unit;
    w.equality = c.equality;
    w.raising_relaxes = c.of != ResponseMeasure::Min;
    w.derivative = d * cost_unit / unit;
    w.tolerance = constraintTolerance(c) * unit;
    out.push_back(w);
  }
  // L's bound terms μᵤ(x − u) + μₗ(l − x) in the scaled x = value/scale: dΨ*/du = −μᵤ/scale, dΨ*/dl = μₗ/scale.
  for (std::size_t j = 0; j < problem.design.variables.size(); ++j) {
    const DesignVariable& v = problem.design.variables[j];
    const auto index = static_cast<Eigen::Index>(j);
    for (const auto kind : {BoundWorth::Kind::LowerBound, BoundWorth::Kind::UpperBound}) {
      const bool lower = kind == BoundWorth::Kind::LowerBound;
      const double mu = lower ? multipliers.lower[index] : multipliers.upper[index];
      if (mu == 0.0) continue;
      BoundWorth w;
      w.kind = kind;
      w.raising_relaxes = !lower;
      w.name = v.parameter;
      w.unit = parameterUnit(model, v.index);
      w.index = static_cast<int>(j);
      w.bound = lower ? v.lower : v.upper;
      w.derivative = (lower ? mu : -mu) / v.scale * cost_unit;
      out.push_back(w);
    }
  }
  return out;
}

double toleranceWorth(const std::vector<BoundWorth>& worth) {
  double sum = 0.0;
  for (const BoundWorth& w : worth) sum += std::abs(w.derivative) * w.tolerance;
  return sum;
}

}  // namespace mbsopt
