// Assembly of an initial state onto the constraint manifold: least-squares (minimum-norm)
// correction of the free coordinates through the SVD of B, by Gauss-Newton, then the velocities
// (minimum-norm correction in joint space).
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/model.hpp"

namespace mbsopt {

struct AssemblyReport {
  double position_correction = 0.0;  ///< ‖Δq‖∞ applied to the free coordinates
  double velocity_correction = 0.0;  ///< ‖Δq̇‖∞
  double closure_error = 0.0;        ///< ‖b(q)‖∞ after assembly
  int iterations = 0;
};

/// A loop that cannot be closed: the cut joints whose equations stay violated.
class AssemblyError : public std::runtime_error {
 public:
  AssemblyError(const std::string& what, std::vector<int> open_cuts)
      : std::runtime_error(what), open_cuts_(std::move(open_cuts)) {}
  const std::vector<int>& openCuts() const { return open_cuts_; }  ///< indices into Model::cuts()

 private:
  std::vector<int> open_cuts_;
};

/// Moves q (then v) onto b(q, t) = 0 (then ḃ = 0); driven coordinates take their prescribed
/// motion at t. Throws AssemblyError naming the cut joints that cannot be closed when the
/// residual does not fall below `tolerance` (a loop that cannot be assembled).
AssemblyReport assemble(const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v, double t,
                        double tolerance = 1e-12, double svd_threshold = 1e-10);

}  // namespace mbsopt
