#include "mbsopt/sensitivity/discrete_adjoint.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "mbsopt/linalg/small_products.hpp"
#include "mbsopt/sensitivity/augmented_solve.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

namespace {

/// The constraints whose adjoint is not exactly zero at this step, into `rows`. Every operation of
/// a backward step maps each constraint's row on its own (linear, row by row), so a zero row stays
/// zero and a step without a non-zero row adds nothing: both are skipped. The result is the same to
/// round-off (the same operations on fewer rows; Eigen's kernels may sum in another order).
void nonZeroRows(const ResponseSeeds& bar, std::vector<Eigen::Index>& rows) {
  rows.clear();
  const Eigen::Index r = bar.position.rows(), n = bar.position.cols();
  const auto nonZero = [&](Eigen::Index j) {  // down row j of the three, column-major
    for (const Eigen::MatrixXd* m : {&bar.position, &bar.velocity, &bar.acceleration})
      for (Eigen::Index i = 0; i < n; ++i)
        if (m->data()[j + i * r] != 0.0) return true;  // (NaN included)
    for (Eigen::Index i = 0; i < bar.multipliers.cols(); ++i)
      if (bar.multipliers(j, i) != 0.0) return true;
    return false;
  };
  for (Eigen::Index j = 0; j < r; ++j)
    if (nonZero(j)) rows.push_back(j);
}

/// What one backward step hands to step k − 1 (the adjoints of the predictors q̃, ṽ of step k, and
/// its contribution to dΨ/db), with its intermediate matrices: kept from step to step, so that the
/// sweep allocates nothing once their sizes are reached.
struct BackwardStep {
  Eigen::MatrixXd q_pred, v_pred, dpsi_db;
  Eigen::MatrixXd a_newton, v_total, a_total, tbar, bbar, iteration, product;
};

/// The transpose of directGradient's step k for the adjoint rows `bar` (the active constraints),
/// into `out`; `solver` is kept from step to step for its buffers.
void backThroughStep(TrajectoryDerivatives& d, const TrajectoryDerivatives::PointDerivatives& point, double h,
                     const ResponseSeeds& bar, AugmentedSolver& solver, BackwardStep& out) {
  const NewmarkSettings& settings = d.settings();
  const double beta = settings.beta, gamma = settings.gamma;
  const StepDerivatives& s = point.step;
  const ClosureDerivatives& c = point.closure;
  const bool loops = d.constraintCount() > 0;
  // q_pred accumulates the adjoint of qₖ, v_pred that of q̇*, until they become those of q̃, ṽ.
  out.q_pred = bar.position;
  out.a_newton = bar.acceleration;
  out.v_pred = bar.velocity;
  out.dpsi_db.setZero(bar.position.rows(), d.variableCount());
  solver.setConstraintPartition(c.partition);  // B's SVD, the point's, for the three solves
  if (loops) {
    // Back through the projections: q̈ₖ = L(M q̈* − G_a qₖ − P_a, −∂b̈/∂q qₖ − ∂b̈/∂q̇ q̇ₖ − ∂b̈/∂b),
    // then q̇ₖ = L(M q̇* − G_v qₖ − P_v, −∂ḃ/∂q qₖ − ∂ḃ/∂b). Each hands the adjoint of its x* to
    // `newton`, adds its share to those of qₖ and b, and leaves its t̄, b̄ in `out`.
    const auto backThroughProjection = [&](const Eigen::MatrixXd& xbar, const Eigen::MatrixXd& G,
                                           const Eigen::MatrixXd& closure_q, const Eigen::MatrixXd& P,
                                           const Eigen::MatrixXd& closure_b, Eigen::MatrixXd& newton) {
      solver.solveTransposed(xbar, out.tbar, out.bbar);
      multiply(out.tbar, s.mass, newton);
      multiply(out.tbar, G, out.product);
      multiply(out.bbar, closure_q, out.product, Accumulate::Add);
      out.q_pred -= out.product;
      multiply(out.tbar, P, out.dpsi_db, Accumulate::Subtract);
      if (closure_b.cols() > 0) multiply(out.bbar, closure_b, out.dpsi_db, Accumulate::Subtract);
    };
    solver.setFactoredSymmetricMatrix(c.partition);  // M = Mᵀ as the point factored it
    backThroughProjection(bar.acceleration, c.acceleration_projection, c.acceleration_q,
                          c.acceleration_projection_parameters, c.acceleration_parameters, out.a_newton);
    out.v_total = bar.velocity;
    out.bbar *= 2.0;  // ∂b̈/∂q̇ = 2 ∂ḃ/∂q (ClosureDerivatives); b̄ is solved for again below
    multiply(out.bbar, c.velocity_q, out.v_total, Accumulate::Subtract);
    backThroughProjection(out.v_total, c.velocity_projection, c.velocity_q, c.velocity_projection_parameters,
                          c.velocity_parameters, out.v_pred);
  }
  // Back through qₖ = q̃ + βh² q̈*, q̇* = ṽ + γh q̈* and Newton's system
  // q̈* = L(−(∂f/∂b + K_T q̃ + C_T ṽ), −(B q̃ + ∂b/∂b) / (βh²)) with A = M + γh C_T + βh² K_T, whose
  // multipliers λₖ the cut reactions read.
  out.a_total = out.a_newton + beta * h * h * out.q_pred + gamma * h * out.v_pred;
  out.iteration = s.mass + gamma * h * s.damping + beta * h * h * s.stiffness;
  solver.setTransposedMatrix(out.iteration);
  if (bar.multipliers.cols() > 0) solver.solveTransposed(out.a_total, bar.multipliers, out.tbar, out.bbar);
  else solver.solveTransposed(out.a_total, out.tbar, out.bbar);
  multiply(out.tbar, s.parameters, out.dpsi_db, Accumulate::Subtract);
  multiply(out.tbar, s.stiffness, out.q_pred, Accumulate::Subtract);
  if (loops) {
    multiply(out.bbar, c.jacobian, out.product);
    out.q_pred -= out.product / (beta * h * h);
    if (c.position_parameters.cols() > 0) {
      multiply(out.bbar, c.position_parameters, out.product);
      out.dpsi_db -= out.product / (beta * h * h);
    }
  }
  multiply(out.tbar, s.damping, out.v_pred, Accumulate::Subtract);
}

/// The rows `rows` of bar, into `out` (reusing its storage).
void copyRows(const ResponseSeeds& bar, const std::vector<Eigen::Index>& rows, ResponseSeeds& out) {
  const auto r = static_cast<Eigen::Index>(rows.size());
  out.position.resize(r, bar.position.cols());
  out.velocity.resize(r, bar.velocity.cols());
  out.acceleration.resize(r, bar.acceleration.cols());
  out.multipliers.resize(r, bar.multipliers.cols());
  for (Eigen::Index i = 0; i < r; ++i) {
    const Eigen::Index j = rows[static_cast<std::size_t>(i)];
    out.position.row(i) = bar.position.row(j);
    out.velocity.row(i) = bar.velocity.row(j);
    out.acceleration.row(i) = bar.acceleration.row(j);
    if (bar.multipliers.cols() > 0) out.multipliers.row(i) = bar.multipliers.row(j);  // (a row of no columns has no data)
  }
}

}  // namespace

DesignGradient adjointGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                               const Eigen::VectorXd& x, const DesignResponse* simulated, int jobs) {
  TrajectoryDerivatives d(problem, functionals, x, simulated, jobs);
  const NewmarkSettings& settings = d.settings();
  const double beta = settings.beta, gamma = settings.gamma;
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(d.functionalCount(), d.variableCount());
  // Adjoints of q_k, q̇_k, q̈_k (one row per constraint): their direct seeds, plus what flows back
  // from the later steps. Each step is the transpose of directGradient's, in reverse order.
  // Nothing flows back from the points after the last one with a seed: the sweep starts there.
  // The sensors' explicit ∂Ψ/∂b at each point, once per point, beside the sweep.
  const auto addExplicit = [&](const ResponseSeeds& seeds) {
    if (seeds.parameters.cols() > 0) dpsi_db += seeds.parameters;
  };
  Eigen::Index k = d.lastSeededPoint();
  ResponseSeeds bar = d.seeds(k), active;
  addExplicit(bar);
  AugmentedSolver solver(settings.svd_threshold);
  BackwardStep back;
  std::vector<Eigen::Index> rows;
  nonZeroRows(bar, rows);
  if (k >= 1) {
    // From there down, the step derivatives and seeds, which do not depend on the sweep, computed
    // ahead on `jobs` threads while the sweep goes back through the steps.
    TrajectoryDerivatives::PointStream points(d, k, 1, jobs);
    const TrajectoryDerivatives::PointDerivatives* point = &points.next();  // its seeds are bar's
    for (;; --k) {
      const double h = d.stepSize(k);  // of step k, from point k − 1
      if (!rows.empty()) {
        copyRows(bar, rows, active);
        backThroughStep(d, *point, h, active, solver, back);
      }
      // Back through the predictor (32) to step k − 1, added to its own seeds.
      if (k > 1) {
        point = &points.next();
        bar = point->seeds;
      } else {
        d.seeds(0, bar);
      }
      addExplicit(bar);
      for (std::size_t i = 0; i < rows.size(); ++i) {
        const Eigen::Index j = rows[i], r = static_cast<Eigen::Index>(i);
        dpsi_db.row(j) += back.dpsi_db.row(r);
        bar.position.row(j) += back.q_pred.row(r);
        bar.velocity.row(j) += h * back.q_pred.row(r) + back.v_pred.row(r);
        bar.acceleration.row(j) += (0.5 - beta) * h * h * back.q_pred.row(r) + (1.0 - gamma) * h * back.v_pred.row(r);
      }
      if (k == 1) break;
      nonZeroRows(bar, rows);
    }
  }
  // t₀: the adjoints of q₀, q̇₀, q̈₀ times their sensitivities, the start of `direct` (the initial
  // state closed on the design's loops, and its accelerations).
  nonZeroRows(bar, rows);
  if (!rows.empty()) {
    const InitialSensitivities initial = d.initialSensitivities();
    dpsi_db(rows, Eigen::all) += bar.position(rows, Eigen::all) * initial.q + bar.velocity(rows, Eigen::all) * initial.v +
                                 bar.acceleration(rows, Eigen::all) * initial.a;
    if (bar.multipliers.cols() > 0) dpsi_db(rows, Eigen::all) += bar.multipliers(rows, Eigen::all) * initial.lambda;
  }
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
