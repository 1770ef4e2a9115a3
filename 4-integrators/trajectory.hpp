// What a run of an integrator leaves: every stored time point's state, multipliers and sensors, and
// the run's counts.
#pragma once

#include <Eigen/Core>

#include "mbsopt/model/model.hpp"

namespace mbsopt {

struct IntegratorStatistics {
  long steps = 0;
  long rejected_steps = 0;  ///< solved and rejected by a step controller (adaptive_newmark.hpp)
  long newton_iterations = 0;
  long jacobian_updates = 0;  ///< full tangent matrices (AD)
  long mass_updates = 0;      ///< mass-matrix-only refreshes of the iteration matrix
  /// Reduced matrices V₂ᵀMV₂ or V₂ᵀJV₂ factored: one per step with position-level closure while J = M
  /// (the projections' factorization serves the next step's Newton iterations), two once J has its
  /// tangent part.
  long factorizations = 0;
  double max_closure_error = 0.0;  ///< max over steps of ‖b(q)‖∞
  /// Max over steps of the last Newton residual evaluated in the step, each row relative to the
  /// magnitude of its terms (NewtonRoundoff; ≈ 1e-14 at round-off). 0 without a position closure.
  double max_relative_residual = 0.0;
};

struct Trajectory {
  Eigen::VectorXd time;                   ///< one entry per stored point (t₀ and every step)
  Eigen::MatrixXd q, v, a, lambda;        ///< one column per time point
  /// q̇ and q̈ as Newton left them, before the projections onto the velocity and acceleration
  /// constraints (equal to v, a without cut joints): the state the exact gradients linearise about.
  Eigen::MatrixXd v_unprojected, a_unprojected;
  /// Every model sensor at every time point, evaluated in the step on its kinematics: rows = time
  /// points, columns = model sensors, the values sensorHistory(model, trajectory) computes again.
  Eigen::MatrixXd sensors;
  Eigen::VectorXd closure_error;          ///< ‖b(q)‖∞ per time point
  Eigen::VectorXi newton_iterations;      ///< per time point (0 at t₀)
  /// When kept (NewmarkIntegrator::keepStepMatrices): per time point, the matrices its projections
  /// used, M(q) on the free coordinates (column-major), B(q) (closure rows × free coordinates), B's
  /// SVD partition (SvdPartition::store), then the partition's factorization of M
  /// (SvdPartition::storeFactorization), in one column laid out as StepMatrixLayout says; no rows
  /// otherwise.
  Eigen::MatrixXd step_matrices;
  IntegratorStatistics statistics;
};

/// Every sensor at every time point of a trajectory (its q, q̇, q̈, λ and t): rows = time points,
/// columns = model sensors. NewmarkIntegrator::simulate records the same values in the step
/// (Trajectory::sensors); this recomputes the kinematics of each stored state.
Eigen::MatrixXd sensorHistory(const Model& model, const Trajectory& trajectory);

}  // namespace mbsopt
