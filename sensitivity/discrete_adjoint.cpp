#include "sensitivity/discrete_adjoint.hpp"

#include "sensitivity/augmented_solve.hpp"
#include "sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

DesignGradient adjointGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                               const Eigen::VectorXd& x) {
  TrajectoryDerivatives d(problem, functionals, x);
  const NewmarkSettings& settings = d.settings();
  const double h = settings.step, beta = settings.beta, gamma = settings.gamma, threshold = settings.svd_threshold;
  const Eigen::Index N = d.timePoints() - 1, nf = d.freeCount(), m = d.constraintCount();
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), d.variableCount());
  Eigen::MatrixXd tbar, bbar;
  // Adjoints of q_k, q̇_k, q̈_k (one row per constraint): their direct seeds, plus what flows back
  // from the later steps. Each step is the transpose of directGradient's, in reverse order.
  ResponseSeeds bar = d.seeds(N);
  for (Eigen::Index k = N; k >= 1; --k) {
    const StepDerivatives s = d.step(k);
    Eigen::MatrixXd q_total = bar.position, a_newton = bar.acceleration, v_newton = bar.velocity;
    Eigen::MatrixXd jacobian(0, nf);
    if (m > 0) {
      // Back through the projections: q̈ₖ = L(M q̈* − G_a qₖ − P_a, −∂b̈/∂q qₖ − ∂b̈/∂q̇ q̇ₖ), then
      // q̇ₖ = L(M q̇* − G_v qₖ − P_v, −∂ḃ/∂q qₖ).
      const ClosureDerivatives c = d.closure(k);
      jacobian = c.jacobian;
      solveAugmentedTransposed(s.mass, jacobian, bar.acceleration, threshold, tbar, bbar);
      a_newton = tbar * s.mass;
      q_total -= tbar * c.acceleration_projection + bbar * c.acceleration_q;
      dpsi_db -= tbar * c.acceleration_projection_parameters;
      const Eigen::MatrixXd v_total = bar.velocity - bbar * c.acceleration_v;
      solveAugmentedTransposed(s.mass, jacobian, v_total, threshold, tbar, bbar);
      v_newton = tbar * s.mass;
      q_total -= tbar * c.velocity_projection + bbar * c.velocity_q;
      dpsi_db -= tbar * c.velocity_projection_parameters;
    }
    // Back through qₖ = q̃ + βh² q̈*, q̇* = ṽ + γh q̈* and Newton's system
    // q̈* = L(−(∂f/∂b + K_T q̃ + C_T ṽ), −B q̃ / (βh²)) with A = M + γh C_T + βh² K_T.
    const Eigen::MatrixXd a_total = a_newton + beta * h * h * q_total + gamma * h * v_newton;
    const Eigen::MatrixXd iteration = s.mass + gamma * h * s.damping + beta * h * h * s.stiffness;
    solveAugmentedTransposed(iteration, jacobian, a_total, threshold, tbar, bbar);
    dpsi_db -= tbar * s.parameters;
    const Eigen::MatrixXd q_pred = q_total - tbar * s.stiffness - bbar * jacobian / (beta * h * h);
    const Eigen::MatrixXd v_pred = v_newton - tbar * s.damping;
    // Back through the predictor (32) to step k − 1, added to its own seeds.
    bar = d.seeds(k - 1);
    bar.position += q_pred;
    bar.velocity += h * q_pred + v_pred;
    bar.acceleration += (0.5 - beta) * h * h * q_pred + (1.0 - gamma) * h * v_pred;
  }
  // t₀: q₀, q̇₀ do not depend on b; q̈₀ = L(−∂f/∂b, 0) with J = M.
  const StepDerivatives s = d.step(0);
  solveAugmentedTransposed(s.mass, d.constraintJacobian(0), bar.acceleration, threshold, tbar, bbar);
  dpsi_db -= tbar * s.parameters;
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
