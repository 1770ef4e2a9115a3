// Assembly of an initial state onto the constraint manifold: least-squares (minimum-norm)
// correction of the free coordinates through the SVD of B, by Gauss-Newton, then the velocities
// (minimum-norm correction in joint space).
#pragma once

#include <Eigen/Core>

#include "dynamics/model.hpp"

namespace mbsopt {

struct AssemblyReport {
  double position_correction = 0.0;  ///< ‖Δq‖∞ applied to the free coordinates
  double velocity_correction = 0.0;  ///< ‖Δq̇‖∞
  double closure_error = 0.0;        ///< ‖b(q)‖∞ after assembly
  int iterations = 0;
};

/// Moves q (then v) onto b(q, t) = 0 (then ḃ = 0); driven coordinates take their prescribed
/// motion at t. Throws std::runtime_error naming the cut joints that cannot be closed when the
/// residual does not fall below `tolerance` (a loop that cannot be assembled).
AssemblyReport assemble(const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v, double t,
                        double tolerance = 1e-12, double svd_threshold = 1e-10);

}  // namespace mbsopt
