#include "sensitivity/direct_sensitivity.hpp"

#include <Eigen/LU>

#include "sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

DesignGradient directGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x) {
  TrajectoryDerivatives d(problem, functionals, x);
  const double h = d.settings().step, beta = d.settings().beta, gamma = d.settings().gamma;
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), d.variableCount());
  const auto accumulate = [&](Eigen::Index k, const Eigen::MatrixXd& Sq, const Eigen::MatrixXd& Sv,
                              const Eigen::MatrixXd& Sa) {
    const ResponseSeeds s = d.seeds(k);
    dpsi_db += s.position * Sq + s.velocity * Sv + s.acceleration * Sa;
  };
  // t₀: q₀ and q̇₀ do not depend on b; f(q₀, q̇₀, q̈₀; b) = 0 gives M S_a = −∂f/∂b.
  const Eigen::Index nf = d.freeCount(), p = d.variableCount();
  Eigen::MatrixXd Sq = Eigen::MatrixXd::Zero(nf, p), Sv = Eigen::MatrixXd::Zero(nf, p);
  StepDerivatives s = d.step(0);
  Eigen::MatrixXd Sa = s.mass.partialPivLu().solve(-s.parameters);
  accumulate(0, Sq, Sv, Sa);
  for (Eigen::Index k = 1; k < d.timePoints(); ++k) {
    // (32): the parts known at tₙ; (33) differentiated at the converged state of step k:
    // (M + γh C_T + βh² K_T) S_a = −(∂f/∂b + K_T S_q̃ + C_T S_ṽ).
    const Eigen::MatrixXd Sq_pred = Sq + h * Sv + (0.5 - beta) * h * h * Sa;
    const Eigen::MatrixXd Sv_pred = Sv + (1.0 - gamma) * h * Sa;
    s = d.step(k);
    const Eigen::MatrixXd iteration = s.mass + gamma * h * s.damping + beta * h * h * s.stiffness;
    Sa = iteration.partialPivLu().solve(-(s.parameters + s.stiffness * Sq_pred + s.damping * Sv_pred));
    Sq = Sq_pred + beta * h * h * Sa;
    Sv = Sv_pred + gamma * h * Sa;
    accumulate(k, Sq, Sv, Sa);
  }
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
