// An orthonormal basis Q = [Q₁ Q₂] of ℝⁿ whose first r columns span those of a given n × r matrix A
// (r ≤ n), from A's Householder QR, A = Q [R; 0], kept as its r reflectors
// H_k = I − τ_k v_k v_kᵀ (v_k zero above row k, one at row k), Q = H_0 H_1 ⋯ H_{r−1}
// (Golub and Van Loan, "Matrix Computations", 4th ed., §5.1-5.2; LAPACK's xGEQR2 and xLARFG).
// Q₂ is then an orthonormal basis of the complement of A's columns. On raw column-major loops: the
// matrices of a Newmark step have a few rows and columns, where Eigen's dynamic-size Householder
// kernels cost ten times their arithmetic (callgrind on BM_TramwaySimulation).
#pragma once

#include <Eigen/Core>

namespace mbsopt {

class HouseholderBasis {
 public:
  /// The reflectors of A (n × r, r ≤ n, full column rank). Allocates nothing once its buffers have
  /// A's size.
  void compute(const Eigen::MatrixXd& a);

  Eigen::Index reflectorCount() const { return tau_.size(); }
  /// The reflectors (n × r, as compute() leaves them) and their τ (r), e.g. to keep and load again.
  const Eigen::MatrixXd& reflectors() const { return reflectors_; }
  const Eigen::VectorXd& tau() const { return tau_; }
  /// Reflectors and τ that compute() left, from raw column-major data (n × r and r entries).
  void assign(const double* reflectors, const double* tau, Eigen::Index n, Eigen::Index r);
  /// Q₂, the last n − r columns of Q, into `out` (resized to n × (n − r)).
  void complement(Eigen::MatrixXd& out) const;
  /// x ← Qᵀ x Q for a square x (n × n): its last n − r rows and columns are then Q₂ᵀ x Q₂, in
  /// O(n² r) instead of the O(n³) of the products with the explicit Q.
  void transformSimilar(Eigen::MatrixXd& x);

 private:
  Eigen::MatrixXd reflectors_;  ///< v_k below the diagonal of column k (its unit entry implied), R above
  Eigen::VectorXd tau_, row_work_;
};

}  // namespace mbsopt
