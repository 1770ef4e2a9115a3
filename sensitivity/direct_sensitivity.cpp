#include "sensitivity/direct_sensitivity.hpp"

#include <Eigen/LU>
#include <stdexcept>

#include "dynamics/tangent.hpp"
#include "sensitivity/parameter_jacobian.hpp"
#include "sensitivity/response_jacobian.hpp"

namespace mbsopt {

namespace {

/// Rows and columns of the free coordinates.
Eigen::MatrixXd freeBlock(const Eigen::MatrixXd& A, const std::vector<int>& free) {
  const auto nf = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd out(nf, nf);
  for (Eigen::Index i = 0; i < nf; ++i)
    for (Eigen::Index j = 0; j < nf; ++j) out(i, j) = A(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]);
  return out;
}

/// Solves A|free X = −R|free rows and writes X into the free rows of S (driven rows stay zero).
void solveFree(const Eigen::MatrixXd& A, const Eigen::MatrixXd& R, const std::vector<int>& free, Eigen::MatrixXd& S) {
  Eigen::MatrixXd rhs(static_cast<Eigen::Index>(free.size()), R.cols());
  for (std::size_t i = 0; i < free.size(); ++i) rhs.row(static_cast<Eigen::Index>(i)) = R.row(free[i]);
  const Eigen::MatrixXd X = freeBlock(A, free).partialPivLu().solve(-rhs);
  S.setZero(R.rows(), R.cols());
  for (std::size_t i = 0; i < free.size(); ++i) S.row(free[i]) = X.row(static_cast<Eigen::Index>(i));
}

}  // namespace

DesignGradient directGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x) {
  if (problem.scene.model.constraintCount() > 0)
    throw std::invalid_argument("direct: scenes with cut joints are not supported yet (use fd)");
  const DesignResponse response = evaluateDesign(problem, functionals, x);
  Model model = problem.scene.model;
  applyDesign(problem, x, model);
  const NewmarkSettings& settings = problem.scene.settings;
  const double h = settings.step, beta = settings.beta, gamma = settings.gamma;
  const Trajectory& tr = response.trajectory;
  const std::vector<int>& free = model.freeCoordinates();
  std::vector<std::string> parameters;
  for (const DesignVariable& v : problem.design.variables) parameters.push_back(v.parameter);
  const auto p = static_cast<Eigen::Index>(parameters.size());
  const Eigen::Index n = model.coordinateCount(), steps = tr.time.size();

  Workspace<AdScalar> ws(model);
  TangentMatrices tangent;
  const Eigen::VectorXd no_lambda;
  // dφ_k/db for every constraint, accumulated into dΨ/db = Σ_k ∂Ψ/∂φ_k dφ_k/db.
  Eigen::MatrixXd gradient = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(functionals.size()), p);
  const auto accumulate = [&](Eigen::Index k, const Eigen::MatrixXd& Sq, const Eigen::MatrixXd& Sv,
                              const Eigen::MatrixXd& Sa) {
    for (std::size_t j = 0; j < functionals.size(); ++j) {
      const ConstraintFunctional& f = functionals[j];
      const double weight = response.functionals[j].gradient[k];
      if (weight == 0.0) continue;
      const ResponseJacobian J = responseJacobian(model, ws, model.sensors()[static_cast<std::size_t>(f.sensor)],
                                                  tr.q.col(k), tr.v.col(k), tr.a.col(k));
      gradient.row(static_cast<Eigen::Index>(j)) +=
          weight * f.sign * (J.position * Sq + J.velocity * Sv + J.acceleration * Sa);
    }
  };

  // t₀: q₀, q̇₀ do not depend on b; f(q₀, q̇₀, q̈₀; b) = 0 gives M S_a = −∂f/∂b.
  Eigen::MatrixXd Sq = Eigen::MatrixXd::Zero(n, p), Sv = Eigen::MatrixXd::Zero(n, p), Sa;
  tangentMatrices(model, ws, tr.q.col(0), tr.v.col(0), tr.a.col(0), no_lambda, tr.time[0], tangent);
  solveFree(tangent.mass, parameterJacobian(model, ws, tr.q.col(0), tr.v.col(0), tr.a.col(0), no_lambda, tr.time[0], parameters),
            free, Sa);
  accumulate(0, Sq, Sv, Sa);
  for (Eigen::Index k = 1; k < steps; ++k) {
    // (32): the parts known at tₙ, then (33) differentiated at the converged state of step k:
    // (M + γh C_T + βh² K_T) S_a = −(∂f/∂b + K_T S_q̃ + C_T S_ṽ).
    const Eigen::MatrixXd Sq_pred = Sq + h * Sv + (0.5 - beta) * h * h * Sa;
    const Eigen::MatrixXd Sv_pred = Sv + (1.0 - gamma) * h * Sa;
    tangentMatrices(model, ws, tr.q.col(k), tr.v.col(k), tr.a.col(k), no_lambda, tr.time[k], tangent);
    const Eigen::MatrixXd dfdb =
        parameterJacobian(model, ws, tr.q.col(k), tr.v.col(k), tr.a.col(k), no_lambda, tr.time[k], parameters);
    const Eigen::MatrixXd iteration = tangent.mass + gamma * h * tangent.damping + beta * h * h * tangent.stiffness;
    solveFree(iteration, dfdb + tangent.stiffness * Sq_pred + tangent.damping * Sv_pred, free, Sa);
    Sq = Sq_pred + beta * h * h * Sa;
    Sv = Sv_pred + gamma * h * Sa;
    accumulate(k, Sq, Sv, Sa);
  }

  DesignGradient out;
  const Eigen::Index nx = x.size();
  out.cost = Eigen::VectorXd::Zero(nx);
  out.cost[nx - 1] = problem.design.artificial.scale;
  out.constraints.resize(static_cast<Eigen::Index>(functionals.size()), nx);
  for (Eigen::Index i = 0; i < p; ++i)
    out.constraints.col(i) = gradient.col(i) * problem.design.variables[static_cast<std::size_t>(i)].scale;
  out.constraints.col(nx - 1) = artificialColumn(problem, functionals, response);
  return out;
}

}  // namespace mbsopt
