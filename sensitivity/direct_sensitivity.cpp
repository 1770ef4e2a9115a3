#include "sensitivity/direct_sensitivity.hpp"

#include <algorithm>
#include <vector>

#include "sensitivity/augmented_solve.hpp"
#include "sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

DesignGradient directGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x, const DesignResponse* simulated, int jobs) {
  TrajectoryDerivatives d(problem, functionals, x, simulated, jobs);
  const NewmarkSettings& settings = d.settings();
  const double h = settings.step, beta = settings.beta, gamma = settings.gamma;
  const Eigen::Index nf = d.freeCount(), p = d.variableCount(), m = d.constraintCount();
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), p);
  const auto accumulate = [&](const ResponseSeeds& s, const Eigen::MatrixXd& Sq, const Eigen::MatrixXd& Sv,
                              const Eigen::MatrixXd& Sa) {
    dpsi_db += s.position * Sq + s.velocity * Sv + s.acceleration * Sa;
  };
  // t₀: q₀ and q̇₀ do not depend on b; f(q₀, q̇₀, q̈₀, λ₀; b) = 0 with b̈ = 0 gives
  // [M Bᵀ; B 0][S_a; S_λ] = [−∂f/∂b; 0].
  Eigen::MatrixXd Sq = Eigen::MatrixXd::Zero(nf, p), Sv = Eigen::MatrixXd::Zero(nf, p);
  const StepDerivatives initial = d.step(0);
  Eigen::MatrixXd Sa = solveAugmented(initial.mass, d.constraintJacobian(0), -initial.parameters,
                                      Eigen::MatrixXd::Zero(m, p), settings.svd_threshold);
  accumulate(d.seeds(0), Sq, Sv, Sa);
  AugmentedSolver solver(settings.svd_threshold);
  // The step derivatives and seeds, which do not depend on the recursion, computed ahead on `jobs`
  // threads while the recursion goes forward.
  TrajectoryDerivatives::PointStream points(d, 1, d.timePoints() - 1, jobs);
  for (Eigen::Index k = 1; k < d.timePoints(); ++k) {
    const TrajectoryDerivatives::PointDerivatives& point = points.next();
    // (32): the parts known at tₙ; then Newton's equations (33) and b(qₙ₊₁) = 0 differentiated at
    // their solution: [A Bᵀ; B 0][S_a*; S_λ] = −[∂f/∂b + K_T S_q̃ + C_T S_ṽ; B S_q̃ / (βh²)],
    // A = M + γh C_T + βh² K_T.
    const Eigen::MatrixXd Sq_pred = Sq + h * Sv + (0.5 - beta) * h * h * Sa;
    const Eigen::MatrixXd Sv_pred = Sv + (1.0 - gamma) * h * Sa;
    const StepDerivatives& s = point.step;
    const ClosureDerivatives& c = point.closure;
    const Eigen::MatrixXd iteration = s.mass + gamma * h * s.damping + beta * h * h * s.stiffness;
    solver.setConstraintJacobian(c.jacobian);  // B's SVD once for the three solves
    solver.setMatrix(iteration);
    const Eigen::MatrixXd Sa_newton =
        solver.solve(-(s.parameters + s.stiffness * Sq_pred + s.damping * Sv_pred), -c.jacobian * Sq_pred / (beta * h * h));
    Sq = Sq_pred + beta * h * h * Sa_newton;
    Sv = Sv_pred + gamma * h * Sa_newton;
    Sa = Sa_newton;
    if (m > 0) {
      // The M-orthogonal projections onto ḃ = 0 and b̈ = 0, differentiated:
      // [M Bᵀ; B 0][S_v; ·] = [M S_v* − G_v S_q − P_v; −∂ḃ/∂q S_q], then the same for q̈ with
      // ∂b̈/∂(q, q̇).
      solver.setMatrix(s.mass);
      Sv = solver.solve(s.mass * Sv - c.velocity_projection * Sq - c.velocity_projection_parameters, -c.velocity_q * Sq);
      Sa = solver.solve(s.mass * Sa_newton - c.acceleration_projection * Sq - c.acceleration_projection_parameters,
                        -(c.acceleration_q * Sq + c.acceleration_v * Sv));
    }
    accumulate(point.seeds, Sq, Sv, Sa);
  }
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
