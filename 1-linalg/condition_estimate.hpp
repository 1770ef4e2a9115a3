// An O(n²) estimate of the reciprocal condition number of a matrix from its LU factors: Hager's
// method as refined by Higham (LAPACK's xLACN2; N. J. Higham, "FORTRAN codes for estimating the
// one-norm of a real or complex matrix", ACM TOMS 14 (1988) 381-396, Algorithm 4.1). It needs a few
// solves with A and Aᵀ instead of the n solves an exact ‖A⁻¹‖₁ takes, and allocates nothing once
// its buffers have the size of A.
#pragma once

#include <Eigen/Core>

#include "mbsopt/linalg/lu_factors.hpp"

namespace mbsopt {

/// A lower bound of the reciprocal condition number 1 / (‖A‖₁ ‖A⁻¹‖₁) from the LU factors, in one
/// O(n²) sweep over each triangle: ‖A⁻¹‖₁ ≤ ‖U⁻¹‖₁ ‖L⁻¹‖₁, and a triangle's inverse is bounded entry
/// by entry by the inverse of its comparison matrix (|t_ii| on the diagonal, −|t_ij| off it), which is
/// non-negative, so its 1-norm is its largest column sum: one triangular solve with a vector of ones
/// (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., §8.3). It can be far below the
/// true value for ill-conditioned triangles, but for a well-conditioned matrix it is a cheap proof
/// that the matrix is not singular, which is all a step needs before it can skip the estimate below.
/// 0 when a pivot is zero or a sum is not finite.
double reciprocalConditionLowerBound(const Eigen::MatrixXd& a, const LuFactors& lu,
                                     Eigen::VectorXd& scratch);

class ConditionEstimator {
 public:
  /// 1 / (‖A‖₁ est‖A⁻¹‖₁) for the matrix `a` and its factors `lu`. est‖A⁻¹‖₁ = ‖A⁻¹x‖₁ for some
  /// ‖x‖₁ = 1, so it never exceeds ‖A⁻¹‖₁ and the result never falls below the exact reciprocal
  /// condition number; Higham reports it is rarely more than 3 times above it. 0 when a solve is
  /// not finite (an exactly singular U).
  double reciprocalCondition(const Eigen::MatrixXd& a, const LuFactors& lu);

 private:
  Eigen::VectorXd x_, y_, z_, w_, sign_;
};

}  // namespace mbsopt
