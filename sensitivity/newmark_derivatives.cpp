#include "sensitivity/newmark_derivatives.hpp"

#include <optional>
#include <stdexcept>

#include <Eigen/SVD>
#include <algorithm>

#include "dynamics/closure.hpp"
#include "dynamics/kinematics.hpp"
#include "dynamics/residual.hpp"
#include "dynamics/tangent.hpp"
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
                                             const Eigen::VectorXd& x)
    : problem_(problem),
      functionals_(functionals),
      x_(x),
      model_(checkedModel(problem, x)),
      response_(evaluateDesign(problem, functionals, x)),
      ws_(model_),
      ws_double_(model_) {
  for (const DesignVariable& v : problem.design.variables) parameters_.push_back(v.parameter);
}

StepDerivatives TrajectoryDerivatives::derivativesAt(Eigen::Index k, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                                                     const Eigen::VectorXd& lambda) {
  const Trajectory& tr = response_.trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::VectorXd q = tr.q.col(k);
  TangentMatrices tangent;
  tangentMatrices(model_, ws_, q, v, a, lambda, tr.time[k], tangent);
  const Eigen::MatrixXd dfdb = parameterJacobian(model_, ws_, q, v, a, lambda, tr.time[k], parameters_);
  return {tangent.mass(free, free), tangent.damping(free, free), tangent.stiffness(free, free), dfdb(free, Eigen::all)};
}

StepDerivatives TrajectoryDerivatives::step(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  return derivativesAt(k, tr.v_unprojected.col(k), tr.a_unprojected.col(k), tr.lambda.col(k));
}

StepDerivatives TrajectoryDerivatives::projectedStep(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(model_.constraintCount());
  if (model_.constraintCount() > 0) {  // Bᵀλ = −f(q, q̇, q̈, 0) on the free rows, least squares
    const Eigen::VectorXd q = tr.q.col(k), v = tr.v.col(k), a = tr.a.col(k);
    Eigen::VectorXd f;
    residual(model_, ws_double_, q, v, a, lambda, tr.time[k], f);
    const Eigen::MatrixXd transposed = constraintJacobian(k).transpose();
    lambda = transposed.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(-f(model_.freeCoordinates()));
  }
  return derivativesAt(k, tr.v.col(k), tr.a.col(k), lambda);
}

namespace {

/// ∂c/∂x of the closure equations at `level`, x = q (which = 0) or q̇ (which = 1), all columns.
Eigen::MatrixXd closureJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& v, const Eigen::VectorXd& a, Derivative level, int which) {
  const Eigen::Index n = model.coordinateCount();
  Eigen::MatrixXd out(model.constraintCount(), n);
  const KinematicsLevel kinematics = level == Derivative::Position   ? KinematicsLevel::Position
                                     : level == Derivative::Velocity ? KinematicsLevel::Velocity
                                                                     : KinematicsLevel::Acceleration;
  VectorX<AdScalar> c;
  for (Eigen::Index first = 0; first < n; first += kMaxAdDirections) {
    const Eigen::Index count = std::min<Eigen::Index>(kMaxAdDirections, n - first);
    const VectorX<AdScalar> q_ad = seededVector(q, which == 0 ? 0 : n, first, count);
    const VectorX<AdScalar> v_ad = seededVector(v, which == 1 ? 0 : n, first, count);
    const VectorX<AdScalar> a_ad = seededVector(a, n, first, count);  // never seeded
    forwardKinematics(model, ws, q_ad, v_ad, a_ad, kinematics);
    closureEquations(model, ws, level, c);
    for (Eigen::Index i = 0; i < c.size(); ++i) out.row(i).segment(first, count) = c[i].derivatives().head(count);
  }
  return out;
}

}  // namespace

Eigen::MatrixXd TrajectoryDerivatives::constraintJacobian(Eigen::Index k) {
  const std::vector<int>& free = model_.freeCoordinates();
  if (model_.constraintCount() == 0) return Eigen::MatrixXd(0, freeCount());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model_.coordinateCount());
  return closureJacobian(model_, ws_, response_.trajectory.q.col(k), zero, zero, Derivative::Velocity, 1)(Eigen::all,
                                                                                                        free);
}

ClosureDerivatives TrajectoryDerivatives::closure(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::Index n = model_.coordinateCount(), m = model_.constraintCount();
  const Eigen::VectorXd q = tr.q.col(k), v = tr.v.col(k), a = tr.a.col(k), zero = Eigen::VectorXd::Zero(n);
  ClosureDerivatives out;
  out.jacobian = constraintJacobian(k);
  out.velocity_q = closureJacobian(model_, ws_, q, v, zero, Derivative::Velocity, 0)(Eigen::all, free);
  out.acceleration_q = closureJacobian(model_, ws_, q, v, a, Derivative::Acceleration, 0)(Eigen::all, free);
  out.acceleration_v = closureJacobian(model_, ws_, q, v, a, Derivative::Acceleration, 1)(Eigen::all, free);
  // f(q, 0, Δ, μ) − f(q, 0, 0, 0) = M Δ + Bᵀμ, so G = K_T(q, 0, Δ, μ) − K_T(q, 0, 0, 0) and
  // P = ∂f/∂b(q, 0, Δ, μ) − ∂f/∂b(q, 0, 0, 0).
  const Eigen::VectorXd no_multipliers = Eigen::VectorXd::Zero(m);
  TangentMatrices base, shifted;
  tangentMatrices(model_, ws_, q, zero, zero, no_multipliers, tr.time[k], base);
  const Eigen::MatrixXd base_parameters = parameterJacobian(model_, ws_, q, zero, zero, no_multipliers, tr.time[k], parameters_);
  const Eigen::MatrixXd mass = base.mass(free, free);
  const Eigen::JacobiSVD<Eigen::MatrixXd> transposed(out.jacobian.transpose(), Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto linearize = [&](const Eigen::VectorXd& correction, Eigen::MatrixXd& G, Eigen::MatrixXd& P) {
    // The projection's multipliers: the minimum-norm μ with Bᵀμ = −M Δ (free rows).
    const Eigen::VectorXd mu = transposed.solve(-mass * correction(free));
    tangentMatrices(model_, ws_, q, zero, correction, mu, tr.time[k], shifted);
    G = (shifted.stiffness - base.stiffness)(free, free);
    P = (parameterJacobian(model_, ws_, q, zero, correction, mu, tr.time[k], parameters_) - base_parameters)(free, Eigen::all);
  };
  linearize(v - tr.v_unprojected.col(k), out.velocity_projection, out.velocity_projection_parameters);
  linearize(a - tr.a_unprojected.col(k), out.acceleration_projection, out.acceleration_projection_parameters);
  return out;
}

ResponseSeeds TrajectoryDerivatives::seeds(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::Index m = functionalCount(), nf = freeCount();
  ResponseSeeds out{Eigen::MatrixXd::Zero(m, nf), Eigen::MatrixXd::Zero(m, nf), Eigen::MatrixXd::Zero(m, nf)};
  std::vector<std::optional<ResponseJacobian>> jacobians(model_.sensors().size());  // ±y share one
  for (Eigen::Index j = 0; j < m; ++j) {
    const ConstraintFunctional& f = functionals_[static_cast<std::size_t>(j)];
    const double weight = f.sign * response_.functionals[static_cast<std::size_t>(j)].gradient[k];  // ∂Ψ/∂φ_k ∂φ/∂y
    if (weight == 0.0) continue;
    auto& cached = jacobians[static_cast<std::size_t>(f.sensor)];
    if (!cached)
      cached = responseJacobian(model_, ws_, model_.sensors()[static_cast<std::size_t>(f.sensor)], tr.q.col(k),
                                tr.v.col(k), tr.a.col(k));
    const ResponseJacobian& J = *cached;
    out.position.row(j) = weight * J.position(free);
    out.velocity.row(j) = weight * J.velocity(free);
    out.acceleration.row(j) = weight * J.acceleration(free);
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
  return out;
}

}  // namespace mbsopt
