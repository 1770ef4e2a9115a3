#include "sensitivity/newmark_derivatives.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <stdexcept>

#include "dynamics/closure.hpp"
#include "dynamics/kinematics.hpp"
#include "dynamics/mass_matrix.hpp"
#include "dynamics/residual.hpp"
#include "dynamics/tangent.hpp"
#include "sensitivity/forward_ad.hpp"
#include "sensitivity/parallel_runs.hpp"
#include "sensitivity/parameter_jacobian.hpp"
#include "sensitivity/response_jacobian.hpp"

namespace mbsopt {

namespace {

Model checkedModel(const DesignProblem& problem, const Eigen::VectorXd& x) {
  if (problem.scene.model.constraintCount() > 0 && problem.scene.settings.closure != ClosureLevel::Position)
    throw std::invalid_argument("exact gradients: loops closed at acceleration level are not supported (use fd)");
  Model model = problem.scene.model;
  applyDesign(problem, x, model);
  return model;
}

}  // namespace

TrajectoryDerivatives::TrajectoryDerivatives(const DesignProblem& problem,
                                             const std::vector<ConstraintFunctional>& functionals,
                                             const Eigen::VectorXd& x, const DesignResponse* simulated)
    : problem_(problem),
      functionals_(functionals),
      x_(x),
      model_(checkedModel(problem, x)),
      response_(simulated ? *simulated : evaluateDesign(problem, functionals, x)),
      scratch_(model_) {
  for (const DesignVariable& v : problem.design.variables) parameters_.push_back(v.parameter);
  parameter_addresses_ = parameterAddresses(model_, parameters_);
  const std::vector<int>& free = model_.freeCoordinates();
  const std::vector<AdInput> free_q = adInputs(AdInput::Kind::Position, free);
  const std::vector<AdInput> free_v = adInputs(AdInput::Kind::Velocity, free);
  const std::vector<AdInput> design = parameterInputs(parameters_.size());
  step_inputs_ = adInputs({free_v, free_q, design});
  closure_rate_inputs_ = adInputs({free_q, free_v});
  projection_inputs_ = adInputs({free_q, design});
}

void TrajectoryDerivatives::geometryAt(Eigen::Index k, Scratch& s) {
  if (k == s.geometry_point) return;
  const Eigen::VectorXd q = response_.trajectory.q.col(k);
  if (model_.constraintCount() > 0) {
    Eigen::VectorXd closure;  // B's pass leaves the rotations, positions and joint axes at q_k in plain_ws
    mbsopt::constraintJacobian(model_, s.plain_ws, q, model_.freeCoordinates(), closure, s.jacobian);
  } else {
    const Eigen::VectorXd rest = Eigen::VectorXd::Zero(model_.coordinateCount());
    forwardKinematics(model_, s.plain_ws, q, rest, rest, KinematicsLevel::Velocity);
    s.jacobian.resize(0, freeCount());
  }
  massMatrix(model_, s.plain_ws, model_.freeCoordinates(), s.mass);
  s.geometry_point = k;
}

StepDerivatives TrajectoryDerivatives::derivativesAt(Eigen::Index k, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                                                     const Eigen::VectorXd& lambda, Scratch& s) {
  // M = ∂f/∂q̈ in double; C_T, K_T and ∂f/∂b in one set of AD passes seeded in the free q̇, the free
  // q and the design parameters only.
  const Trajectory& tr = response_.trajectory;
  const Eigen::Index nf = freeCount();
  const Eigen::MatrixXd derivatives =
      residualJacobian(model_, s.ws, tr.q.col(k), v, a, lambda, tr.time[k], step_inputs_,
                       parameter_addresses_)(model_.freeCoordinates(), Eigen::all);
  geometryAt(k, s);
  return {s.mass, derivatives.leftCols(nf), derivatives.middleCols(nf, nf), derivatives.rightCols(variableCount())};
}

StepDerivatives TrajectoryDerivatives::stepAt(Eigen::Index k, Scratch& s) {
  const Trajectory& tr = response_.trajectory;
  return derivativesAt(k, tr.v_unprojected.col(k), tr.a_unprojected.col(k), tr.lambda.col(k), s);
}

StepDerivatives TrajectoryDerivatives::step(Eigen::Index k) { return stepAt(k, scratch_); }

StepDerivatives TrajectoryDerivatives::projectedStep(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(model_.constraintCount());
  if (model_.constraintCount() > 0) {  // Bᵀλ = −f(q, q̇, q̈, 0) on the free rows, least squares
    const Eigen::VectorXd q = tr.q.col(k), v = tr.v.col(k), a = tr.a.col(k);
    Eigen::VectorXd f;
    residual(model_, scratch_.plain_ws, q, v, a, lambda, tr.time[k], f);
    const Eigen::MatrixXd transposed = constraintJacobian(k).transpose();
    lambda = transposed.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(-f(model_.freeCoordinates()));
  }
  return derivativesAt(k, tr.v.col(k), tr.a.col(k), lambda, scratch_);
}

namespace {

/// ∂ḃ/∂q, ∂b̈/∂q and ∂b̈/∂q̇ at (q, q̇, q̈): the closure rates [ḃ; b̈] of one kinematics evaluation
/// per AD pass, `inputs` being q then q̇ on the same nc columns (ḃ does not depend on q̈).
void closureRateJacobians(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& v, const Eigen::VectorXd& a, const std::vector<AdInput>& inputs,
                          ClosureDerivatives& out) {
  const auto nc = static_cast<Eigen::Index>(inputs.size() / 2);
  const Eigen::Index m = model.constraintCount();
  thread_local VectorX<AdScalar> velocity, acceleration;
  const Eigen::MatrixXd rates = adJacobian(ws, q, v, a, inputs, {}, 2 * m, [&](const SeededState& s, VectorX<AdScalar>& g) {
    forwardKinematics(model, ws, s.q, s.v, s.a, KinematicsLevel::Acceleration);
    closureEquations(model, ws, Derivative::Velocity, velocity);
    closureEquations(model, ws, Derivative::Acceleration, acceleration);
    g.resize(2 * m);
    g << velocity, acceleration;
  });
  out.velocity_q = rates.topLeftCorner(m, nc);
  out.acceleration_q = rates.bottomLeftCorner(m, nc);
  out.acceleration_v = rates.bottomRightCorner(m, nc);
}

/// [G P] = ∂(M(q)Δ + B(q)ᵀμ)/∂(q, b) on `inputs` (the free q, then the design parameters): one
/// projection's dependence on q and b through M and B (Δ its correction, μ its multipliers), free rows.
Eigen::MatrixXd projectionJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& correction, const Eigen::VectorXd& mu,
                                   const std::vector<AdInput>& inputs, const std::vector<const double*>& parameters) {
  seedVector(mu, 0, 0, 0, ws.seeded_lambda);  // constant
  const VectorX<AdScalar>& mu_ad = ws.seeded_lambda;
  const Eigen::VectorXd unused_rates = Eigen::VectorXd::Zero(q.size());  // M Δ + Bᵀμ is taken at q̇ = 0
  const Eigen::MatrixXd out = adJacobian(ws, q, unused_rates, correction, inputs, parameters, model.coordinateCount(),
                                         [&](const SeededState& s, VectorX<AdScalar>& f) {
                                           inertialAndLoopForces(model, ws, s.q, s.a, mu_ad, f);
                                         });
  return out(model.freeCoordinates(), Eigen::all);
}

}  // namespace

Eigen::MatrixXd TrajectoryDerivatives::constraintJacobian(Eigen::Index k) {
  geometryAt(k, scratch_);
  return scratch_.jacobian;
}

ClosureDerivatives TrajectoryDerivatives::closureAt(Eigen::Index k, Scratch& s) {
  const Trajectory& tr = response_.trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::VectorXd q = tr.q.col(k);
  ClosureDerivatives out;
  geometryAt(k, s);
  out.jacobian = s.jacobian;
  const Eigen::MatrixXd& mass = s.mass;
  closureRateJacobians(model_, s.ws, q, tr.v.col(k), tr.a.col(k), closure_rate_inputs_, out);
  const Eigen::JacobiSVD<Eigen::MatrixXd> transposed(out.jacobian.transpose(), Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto linearize = [&](const Eigen::VectorXd& correction, Eigen::MatrixXd& G, Eigen::MatrixXd& P) {
    // The projection's multipliers: the minimum-norm μ with Bᵀμ = −M Δ (free rows).
    const Eigen::VectorXd mu = transposed.solve(-mass * correction(free));
    const Eigen::MatrixXd derivatives =
        projectionJacobian(model_, s.ws, q, correction, mu, projection_inputs_, parameter_addresses_);
    G = derivatives.leftCols(freeCount());
    P = derivatives.rightCols(variableCount());
  };
  linearize(tr.v.col(k) - tr.v_unprojected.col(k), out.velocity_projection, out.velocity_projection_parameters);
  linearize(tr.a.col(k) - tr.a_unprojected.col(k), out.acceleration_projection, out.acceleration_projection_parameters);
  return out;
}

ClosureDerivatives TrajectoryDerivatives::closure(Eigen::Index k) { return closureAt(k, scratch_); }

std::vector<TrajectoryDerivatives::PointDerivatives> TrajectoryDerivatives::points(Eigen::Index first,
                                                                                   Eigen::Index last, int jobs) {
  const auto count = static_cast<std::size_t>(std::max<Eigen::Index>(last - first + 1, 0));
  std::vector<PointDerivatives> out(count);
  const auto threads = static_cast<std::size_t>(std::clamp<Eigen::Index>(jobs, 1, std::max<Eigen::Index>(count, 1)));
  const auto compute = [&](std::size_t i, Scratch& s) {
    const Eigen::Index k = first + static_cast<Eigen::Index>(i);
    out[i].step = stepAt(k, s);
    if (model_.constraintCount() > 0) out[i].closure = closureAt(k, s);
    out[i].seeds = seedsAt(k, s);
  };
  if (threads == 1) {
    for (std::size_t i = 0; i < count; ++i) compute(i, scratch_);
    return out;
  }
  while (thread_scratch_.size() < threads) thread_scratch_.emplace_back(model_);
  // Thread t takes the points t, t + threads, …: neighbours share no work, the load is even.
  runInParallel(threads, static_cast<int>(threads), [&](std::size_t t) {
    for (std::size_t i = t; i < count; i += threads) compute(i, thread_scratch_[t]);
  });
  return out;
}

ResponseSeeds TrajectoryDerivatives::seeds(Eigen::Index k) { return seedsAt(k, scratch_); }

ResponseSeeds TrajectoryDerivatives::seedsAt(Eigen::Index k, Scratch& scratch) {
  const Trajectory& tr = response_.trajectory;
  const Eigen::Index m = functionalCount(), nf = freeCount();
  ResponseSeeds out{Eigen::MatrixXd::Zero(m, nf), Eigen::MatrixXd::Zero(m, nf), Eigen::MatrixXd::Zero(m, nf)};
  const auto weight = [&](Eigen::Index j) {  // ∂Ψ/∂φ_k ∂φ/∂y
    const auto f = static_cast<std::size_t>(j);
    return functionals_[f].sign * response_.functionals[f].gradient[k];
  };
  // The sensors some constraint is sensitive to at k, each once (±y share one), in one set of passes.
  std::vector<int> slot(model_.sensors().size(), -1);
  std::vector<const Sensor*> sensors;
  for (Eigen::Index j = 0; j < m; ++j) {
    const auto sensor = static_cast<std::size_t>(functionals_[static_cast<std::size_t>(j)].sensor);
    if (weight(j) == 0.0 || slot[sensor] >= 0) continue;
    slot[sensor] = static_cast<int>(sensors.size());
    sensors.push_back(&model_.sensors()[sensor]);
  }
  if (sensors.empty()) return out;
  const std::vector<ResponseJacobian> jacobians =
      responseJacobians(model_, scratch.ws, sensors, tr.q.col(k), tr.v.col(k), tr.a.col(k), model_.freeCoordinates());
  for (Eigen::Index j = 0; j < m; ++j) {
    if (weight(j) == 0.0) continue;
    const ResponseJacobian& J =
        jacobians[static_cast<std::size_t>(slot[static_cast<std::size_t>(functionals_[static_cast<std::size_t>(j)].sensor)])];
    out.position.row(j) = weight(j) * J.position;
    out.velocity.row(j) = weight(j) * J.velocity;
    out.acceleration.row(j) = weight(j) * J.acceleration;
  }
  return out;
}

DesignGradient TrajectoryDerivatives::gradient(const Eigen::MatrixXd& dpsi_db) const {
  const Eigen::Index nx = x_.size();
  DesignGradient out;
  out.cost = Eigen::VectorXd::Zero(nx);
  out.cost[nx - 1] = problem_.design.artificial.scale;  // the cost is b_{k+1} = x_{k+1} · scale
  out.constraints.resize(functionalCount(), nx);
  for (Eigen::Index i = 0; i < variableCount(); ++i)
    out.constraints.col(i) = dpsi_db.col(i) * problem_.design.variables[static_cast<std::size_t>(i)].scale;
  out.constraints.col(nx - 1) = artificialColumn(problem_, functionals_, response_);
  out.values = DesignValues{response_.cost, response_.constraints};
  return out;
}

}  // namespace mbsopt
