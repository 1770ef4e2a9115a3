#include "sensitivity/discrete_adjoint.hpp"

#include <Eigen/LU>

#include "sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

DesignGradient adjointGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                               const Eigen::VectorXd& x) {
  if (problem.scene.model.constraintCount() > 0)
    throw std::invalid_argument("adjoint: scenes with cut joints are not supported yet (use direct or fd)");
  TrajectoryDerivatives d(problem, functionals, x);
  const double h = d.settings().step, beta = d.settings().beta, gamma = d.settings().gamma;
  const Eigen::Index N = d.timePoints() - 1;
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), d.variableCount());
  // Adjoints of q_k, q̇_k, q̈_k (one row per constraint): their direct seeds, plus what flows back
  // from the later steps through the predictor (32).
  ResponseSeeds bar = d.seeds(N);
  for (Eigen::Index k = N; k >= 1; --k) {
    const StepDerivatives s = d.step(k);
    // Step k: q_k = q̃ + βh² q̈_k, q̇_k = ṽ + γh q̈_k, with q̈_k solving f = 0 (33); its total adjoint
    // ā + βh² q̄ + γh v̄ passes through the transposed exact iteration matrix: Aᵀ μᵀ = −(…)ᵀ.
    const Eigen::MatrixXd a_total = bar.acceleration + beta * h * h * bar.position + gamma * h * bar.velocity;
    const Eigen::MatrixXd iteration = s.mass + gamma * h * s.damping + beta * h * h * s.stiffness;
    const Eigen::MatrixXd mu = iteration.transpose().partialPivLu().solve(-a_total.transpose()).transpose();
    dpsi_db += mu * s.parameters;
    const Eigen::MatrixXd q_pred = bar.position + mu * s.stiffness;  // adjoints of q̃ and ṽ
    const Eigen::MatrixXd v_pred = bar.velocity + mu * s.damping;
    // Back through the predictor to step k − 1, added to its own seeds.
    bar = d.seeds(k - 1);
    bar.position += q_pred;
    bar.velocity += h * q_pred + v_pred;
    bar.acceleration += (0.5 - beta) * h * h * q_pred + (1.0 - gamma) * h * v_pred;
  }
  // t₀: q₀, q̇₀ do not depend on b; q̈₀ solves f(q₀, q̇₀, q̈₀; b) = 0, so Mᵀ μᵀ = −āᵀ.
  const StepDerivatives s = d.step(0);
  const Eigen::MatrixXd mu = s.mass.transpose().partialPivLu().solve(-bar.acceleration.transpose()).transpose();
  dpsi_db += mu * s.parameters;
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
