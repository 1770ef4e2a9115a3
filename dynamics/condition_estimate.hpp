// An O(n²) estimate of the reciprocal condition number of a matrix from its LU factors: Hager's
// method as refined by Higham (LAPACK's xLACN2; N. J. Higham, "FORTRAN codes for estimating the
// one-norm of a real or complex matrix", ACM TOMS 14 (1988) 381-396, Algorithm 4.1). It needs a few
// solves with A and Aᵀ instead of the n solves an exact ‖A⁻¹‖₁ takes, and allocates nothing once
// its buffers have the size of A.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace mbsopt {

class ConditionEstimator {
 public:
  /// 1 / (‖A‖₁ est‖A⁻¹‖₁) for the matrix `a` and its factors `lu`. est‖A⁻¹‖₁ = ‖A⁻¹x‖₁ for some
  /// ‖x‖₁ = 1, so it never exceeds ‖A⁻¹‖₁ and the result never falls below the exact reciprocal
  /// condition number; Higham reports it is rarely more than 3 times above it. 0 when a solve is
  /// not finite (an exactly singular U).
  double reciprocalCondition(const Eigen::MatrixXd& a, const Eigen::PartialPivLU<Eigen::MatrixXd>& lu);

 private:
  Eigen::VectorXd x_, y_, z_, w_, sign_;
};

}  // namespace mbsopt
