#include "sensitivity/discrete_adjoint.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "sensitivity/augmented_solve.hpp"
#include "sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

namespace {

/// The constraints whose adjoint is not exactly zero at this step. Every operation of a backward
/// step maps each constraint's row on its own (linear, row by row), so a zero row stays zero and a
/// step without a non-zero row adds nothing: both are skipped. The result is the same to round-off
/// (the same operations on fewer rows; Eigen's kernels may sum in another order).
std::vector<Eigen::Index> nonZeroRows(const ResponseSeeds& bar) {
  std::vector<Eigen::Index> rows;
  for (Eigen::Index j = 0; j < bar.position.rows(); ++j)
    if (!bar.position.row(j).isZero(0.0) || !bar.velocity.row(j).isZero(0.0) || !bar.acceleration.row(j).isZero(0.0))
      rows.push_back(j);
  return rows;
}

/// What one backward step hands to step k − 1: the adjoints of the predictors q̃, ṽ of step k, and
/// its contribution to dΨ/db.
struct BackwardStep {
  Eigen::MatrixXd q_pred, v_pred, dpsi_db;
};

/// The transpose of directGradient's step k for the adjoint rows `bar` (the active constraints);
/// `solver` is kept from step to step for its buffers.
BackwardStep backThroughStep(TrajectoryDerivatives& d, const TrajectoryDerivatives::PointDerivatives& point,
                             const ResponseSeeds& bar, AugmentedSolver& solver) {
  const NewmarkSettings& settings = d.settings();
  const double h = settings.step, beta = settings.beta, gamma = settings.gamma;
  const StepDerivatives& s = point.step;
  const ClosureDerivatives& c = point.closure;
  Eigen::MatrixXd q_total = bar.position, a_newton = bar.acceleration, v_newton = bar.velocity;
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(bar.position.rows(), d.variableCount());
  Eigen::MatrixXd jacobian(0, d.freeCount()), tbar, bbar;
  if (d.constraintCount() > 0) jacobian = c.jacobian;
  solver.setConstraintJacobian(jacobian);  // B's SVD once for the three solves
  if (d.constraintCount() > 0) {
    // Back through the projections: q̈ₖ = L(M q̈* − G_a qₖ − P_a, −∂b̈/∂q qₖ − ∂b̈/∂q̇ q̇ₖ), then
    // q̇ₖ = L(M q̇* − G_v qₖ − P_v, −∂ḃ/∂q qₖ).
    solver.setTransposedMatrix(s.mass);
    solver.solveTransposed(bar.acceleration, tbar, bbar);
    a_newton = tbar * s.mass;
    q_total -= tbar * c.acceleration_projection + bbar * c.acceleration_q;
    dpsi_db -= tbar * c.acceleration_projection_parameters;
    const Eigen::MatrixXd v_total = bar.velocity - bbar * c.acceleration_v;
    solver.solveTransposed(v_total, tbar, bbar);
    v_newton = tbar * s.mass;
    q_total -= tbar * c.velocity_projection + bbar * c.velocity_q;
    dpsi_db -= tbar * c.velocity_projection_parameters;
  }
  // Back through qₖ = q̃ + βh² q̈*, q̇* = ṽ + γh q̈* and Newton's system
  // q̈* = L(−(∂f/∂b + K_T q̃ + C_T ṽ), −B q̃ / (βh²)) with A = M + γh C_T + βh² K_T.
  const Eigen::MatrixXd a_total = a_newton + beta * h * h * q_total + gamma * h * v_newton;
  solver.setTransposedMatrix(s.mass + gamma * h * s.damping + beta * h * h * s.stiffness);
  solver.solveTransposed(a_total, tbar, bbar);
  dpsi_db -= tbar * s.parameters;
  return {q_total - tbar * s.stiffness - bbar * jacobian / (beta * h * h), v_newton - tbar * s.damping, dpsi_db};
}

ResponseSeeds rowsOf(const ResponseSeeds& bar, const std::vector<Eigen::Index>& rows) {
  return {bar.position(rows, Eigen::all), bar.velocity(rows, Eigen::all), bar.acceleration(rows, Eigen::all)};
}

}  // namespace

DesignGradient adjointGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                               const Eigen::VectorXd& x, const DesignResponse* simulated, int jobs) {
  TrajectoryDerivatives d(problem, functionals, x, simulated);
  const NewmarkSettings& settings = d.settings();
  const double h = settings.step, beta = settings.beta, gamma = settings.gamma;
  const Eigen::Index N = d.timePoints() - 1;
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), d.variableCount());
  // Adjoints of q_k, q̇_k, q̈_k (one row per constraint): their direct seeds, plus what flows back
  // from the later steps. Each step is the transpose of directGradient's, in reverse order.
  ResponseSeeds bar = d.seeds(N);
  AugmentedSolver solver(settings.svd_threshold);
  // The step derivatives and seeds, which do not depend on the sweep, in blocks of points computed
  // on `jobs` threads, from the first step with a non-zero adjoint down.
  std::vector<TrajectoryDerivatives::PointDerivatives> block;
  Eigen::Index block_first = 0;
  for (Eigen::Index k = N; k >= 1; --k) {
    const std::vector<Eigen::Index> rows = nonZeroRows(bar);
    if (rows.empty()) {  // nothing flows back yet: no derivative of this step is needed
      bar = d.seeds(k - 1);
      continue;
    }
    if (block.empty() || k < block_first) {
      block_first = std::max<Eigen::Index>(1, k - TrajectoryDerivatives::kPointsPerBlock + 1);
      block = d.points(block_first, k, jobs);
    }
    const BackwardStep back = backThroughStep(d, block[static_cast<std::size_t>(k - block_first)], rowsOf(bar, rows), solver);
    dpsi_db(rows, Eigen::all) += back.dpsi_db;
    // Back through the predictor (32) to step k − 1, added to its own seeds.
    bar = k - 1 >= block_first ? std::move(block[static_cast<std::size_t>(k - 1 - block_first)].seeds) : d.seeds(k - 1);
    bar.position(rows, Eigen::all) += back.q_pred;
    bar.velocity(rows, Eigen::all) += h * back.q_pred + back.v_pred;
    bar.acceleration(rows, Eigen::all) += (0.5 - beta) * h * h * back.q_pred + (1.0 - gamma) * h * back.v_pred;
  }
  // t₀: q₀, q̇₀ do not depend on b; q̈₀ = L(−∂f/∂b, 0) with J = M.
  if (const std::vector<Eigen::Index> rows = nonZeroRows(bar); !rows.empty()) {
    const StepDerivatives s = d.step(0);
    Eigen::MatrixXd tbar, bbar;
    solveAugmentedTransposed(s.mass, d.constraintJacobian(0), bar.acceleration(rows, Eigen::all),
                             settings.svd_threshold, tbar, bbar);
    dpsi_db(rows, Eigen::all) -= tbar * s.parameters;
  }
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
