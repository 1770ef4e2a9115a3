#include "sensitivity/newmark_derivatives.hpp"

#include <stdexcept>

#include "dynamics/tangent.hpp"
#include "sensitivity/parameter_jacobian.hpp"
#include "sensitivity/response_jacobian.hpp"

namespace mbsopt {

namespace {

Model checkedModel(const DesignProblem& problem, const Eigen::VectorXd& x) {
  if (problem.scene.model.constraintCount() > 0)
    throw std::invalid_argument("exact gradients: scenes with cut joints are not supported yet (use fd)");
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
      ws_(model_) {
  for (const DesignVariable& v : problem.design.variables) parameters_.push_back(v.parameter);
}

StepDerivatives TrajectoryDerivatives::step(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::VectorXd no_lambda;
  TangentMatrices tangent;
  tangentMatrices(model_, ws_, tr.q.col(k), tr.v.col(k), tr.a.col(k), no_lambda, tr.time[k], tangent);
  const Eigen::MatrixXd dfdb =
      parameterJacobian(model_, ws_, tr.q.col(k), tr.v.col(k), tr.a.col(k), no_lambda, tr.time[k], parameters_);
  return {tangent.mass(free, free), tangent.damping(free, free), tangent.stiffness(free, free), dfdb(free, Eigen::all)};
}

ResponseSeeds TrajectoryDerivatives::seeds(Eigen::Index k) {
  const Trajectory& tr = response_.trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::Index m = functionalCount(), nf = freeCount();
  ResponseSeeds out{Eigen::MatrixXd::Zero(m, nf), Eigen::MatrixXd::Zero(m, nf), Eigen::MatrixXd::Zero(m, nf)};
  for (Eigen::Index j = 0; j < m; ++j) {
    const ConstraintFunctional& f = functionals_[static_cast<std::size_t>(j)];
    const double weight = f.sign * response_.functionals[static_cast<std::size_t>(j)].gradient[k];  // ∂Ψ/∂φ_k ∂φ/∂y
    if (weight == 0.0) continue;
    const ResponseJacobian J = responseJacobian(model_, ws_, model_.sensors()[static_cast<std::size_t>(f.sensor)],
                                                tr.q.col(k), tr.v.col(k), tr.a.col(k));
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
