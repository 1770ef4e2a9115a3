#include "mbsopt/sensitivity/direct_sensitivity.hpp"

#include <algorithm>
#include <vector>

#include "mbsopt/linalg/small_products.hpp"
#include "mbsopt/sensitivity/augmented_solve.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

namespace {

/// The sensitivities S_q, S_v, S_a of one time point and the intermediate matrices of a step: kept
/// from step to step, so that the recursion allocates nothing once their sizes are reached.
struct ForwardStep {
  Eigen::MatrixXd q, v, a, lambda;  ///< S_λ: Newton's multipliers, as the cut reactions read them
  Eigen::MatrixXd q_pred, v_pred, iteration, top, bottom, a_newton, seeded;
};

/// dΨ/db += ∂Ψ/∂q S_q + ∂Ψ/∂q̇ S_v + ∂Ψ/∂q̈ S_a + ∂Ψ/∂λ S_λ, and the sensors' explicit ∂Ψ/∂b;
/// nothing at a point without seeds.
void accumulate(const ResponseSeeds& seeds, ForwardStep& step, Eigen::MatrixXd& dpsi_db) {
  if (seeds.parameters.cols() > 0) dpsi_db += seeds.parameters;
  if (seeds.multipliers.cols() > 0) dpsi_db.noalias() += seeds.multipliers * step.lambda;
  if (seeds.position.isZero(0.0) && seeds.velocity.isZero(0.0) && seeds.acceleration.isZero(0.0)) return;
  multiply(seeds.position, step.q, step.seeded);
  multiply(seeds.velocity, step.v, step.seeded, Accumulate::Add);
  multiply(seeds.acceleration, step.a, step.seeded, Accumulate::Add);
  dpsi_db += step.seeded;
}

}  // namespace

DesignGradient directGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x, const DesignResponse* simulated, int jobs) {
  TrajectoryDerivatives d(problem, functionals, x, simulated, jobs);
  const NewmarkSettings& settings = d.settings();
  const double beta = settings.beta, gamma = settings.gamma;
  const Eigen::Index p = d.variableCount(), m = d.constraintCount();
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), p);
  // t₀: the initial state closed on the design's loops, and its accelerations.
  ForwardStep step;
  InitialSensitivities initial = d.initialSensitivities();
  step.q.swap(initial.q);
  step.v.swap(initial.v);
  step.a.swap(initial.a);
  step.lambda.swap(initial.lambda);
  accumulate(d.seeds(0), step, dpsi_db);
  AugmentedSolver solver(settings.svd_threshold);
  // The recursion goes as far as the last point with a seed: beyond it the sensitivities would only
  // be multiplied by zero seeds. The step derivatives and seeds, which do not depend on the
  // recursion, computed ahead on `jobs` threads while the recursion goes forward.
  const Eigen::Index last = d.lastSeededPoint();
  if (last == 0) return d.gradient(dpsi_db);
  TrajectoryDerivatives::PointStream points(d, 1, last, jobs);
  for (Eigen::Index k = 1; k <= last; ++k) {
    const TrajectoryDerivatives::PointDerivatives& point = points.next();
    const double h = d.stepSize(k);
    // (32): the parts known at tₙ; then the step's equations (28) and b(qₙ₊₁) = 0, the system
    // (39)-(41) with the iteration matrix (33), differentiated at their solution:
    // [A Bᵀ; B 0][S_a*; S_λ] = −[∂f/∂b + K_T S_q̃ + C_T S_ṽ; (B S_q̃ + ∂b/∂b) / (βh²)],
    // A = M + γh C_T + βh² K_T.
    step.q_pred = step.q + h * step.v + (0.5 - beta) * h * h * step.a;
    step.v_pred = step.v + (1.0 - gamma) * h * step.a;
    const StepDerivatives& s = point.step;
    const ClosureDerivatives& c = point.closure;
    step.iteration = s.mass + gamma * h * s.damping + beta * h * h * s.stiffness;
    solver.setConstraintPartition(c.partition);  // B's SVD, the point's, for the three solves
    solver.setMatrix(step.iteration);
    step.top = s.parameters;
    multiply(s.stiffness, step.q_pred, step.top, Accumulate::Add);
    multiply(s.damping, step.v_pred, step.top, Accumulate::Add);
    multiply(c.jacobian, step.q_pred, step.bottom);
    if (c.position_parameters.cols() > 0) step.bottom += c.position_parameters;
    if (d.readsMultipliers()) solver.solve(-step.top, -step.bottom / (beta * h * h), step.a_newton, step.lambda);
    else solver.solve(-step.top, -step.bottom / (beta * h * h), step.a_newton);
    step.q = step.q_pred + beta * h * h * step.a_newton;
    step.v = step.v_pred + gamma * h * step.a_newton;
    if (m > 0) {
      // The M-orthogonal projections onto ḃ = 0 and b̈ = 0, differentiated:
      // [M Bᵀ; B 0][S_v; ·] = [M S_v* − G_v S_q − P_v; −∂ḃ/∂q S_q − ∂ḃ/∂b], then the same for q̈
      // with ∂b̈/∂(q, q̇, b).
      solver.setFactoredSymmetricMatrix(c.partition);  // M as the point factored it
      multiply(s.mass, step.v, step.top);
      multiply(c.velocity_projection, step.q, step.top, Accumulate::Subtract);
      step.top -= c.velocity_projection_parameters;
      multiply(c.velocity_q, step.q, step.bottom);
      if (c.velocity_parameters.cols() > 0) step.bottom += c.velocity_parameters;
      solver.solve(step.top, -step.bottom, step.v);
      multiply(s.mass, step.a_newton, step.top);
      multiply(c.acceleration_projection, step.q, step.top, Accumulate::Subtract);
      step.top -= c.acceleration_projection_parameters;
      multiply(c.velocity_q, step.v, step.bottom);
      step.bottom *= 2.0;  // ∂b̈/∂q̇ S_v = 2 ∂ḃ/∂q S_v (ClosureDerivatives)
      multiply(c.acceleration_q, step.q, step.bottom, Accumulate::Add);
      if (c.acceleration_parameters.cols() > 0) step.bottom += c.acceleration_parameters;
      solver.solve(step.top, -step.bottom, step.a);
    } else {
      step.a.swap(step.a_newton);
    }
    accumulate(point.seeds, step, dpsi_db);
  }
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
