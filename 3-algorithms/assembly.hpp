// Assembly of an initial state onto the constraint manifold: least-squares (minimum-norm)
// correction of the free coordinates through the SVD of B, by Gauss-Newton, then the velocities
// (minimum-norm correction in joint space).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

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
  AssemblyError(const std::string& what, std::vector<int> open_cuts, double closure_error)
      : std::runtime_error(what), open_cuts_(std::move(open_cuts)), closure_error_(closure_error) {}
  const std::vector<int>& openCuts() const { return open_cuts_; }  ///< indices into Model::cuts()
  double closureError() const { return closure_error_; }            ///< ‖b(q)‖∞ where the corrections ended [m]

 private:
  std::vector<int> open_cuts_;
  double closure_error_;
};

/// The correction of the free coordinates a Gauss-Newton step on b(q) = 0 subtracts, from b and
/// B = ∂b/∂q (free columns) at the current q.
using ClosureCorrection = std::function<void(const Eigen::VectorXd& b, const Eigen::MatrixXd& B, Eigen::VectorXd& correction)>;

/// Gauss-Newton on b(q) = 0: q[free] −= correction(b, B) until max |b| ≤ `tolerance`, at most 50
/// corrections, and no more once 10 have not lowered it by 0.1 % (a loop that cannot be closed).
/// Leaves b and B at the final q, and the geometry at q in ws; returns the corrections made.
int closeLoops(const Model& model, Workspace<double>& ws, Eigen::VectorXd& q, double tolerance,
               const ClosureCorrection& correction, Eigen::VectorXd& b, Eigen::MatrixXd& B);

/// Throws AssemblyError naming the cut joints with a row of b above 1e-9: "CONTEXTthe loop(s)
/// closed by NAMES cannot be assembled: closure error E mDETAIL".
[[noreturn]] void throwOpenLoops(const Model& model, const Eigen::VectorXd& b, const std::string& context,
                                 const std::string& detail);

/// Moves q (then v) onto b(q, t) = 0 (then ḃ = 0); driven coordinates take their prescribed
/// motion at t. Throws AssemblyError naming the cut joints that cannot be closed when the
/// residual does not fall below `tolerance` (a loop that cannot be assembled).
AssemblyReport assemble(const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v, double t,
                        double tolerance = 1e-12, double svd_threshold = 1e-10);

}  // namespace mbsopt
