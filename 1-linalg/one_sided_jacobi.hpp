// Singular value decomposition of a matrix with few columns by one-sided Jacobi rotations
// (M. R. Hestenes, J. SIAM 6 (1958) 51-90; J. Demmel and K. Veselić, "Jacobi's method is more
// accurate than QR", SIAM J. Matrix Anal. Appl. 13 (1992) 1204-1245): plane rotations W applied on
// the right make the columns of A W mutually orthogonal, so A W = X Σ with Σ the column norms and X
// their directions, and A = X Σ Wᵀ. A sweep over the column pairs costs O(rows · cols²), and the
// sweeps converge quadratically. For the transposed constraint Jacobian of a Newmark step (a handful
// of closure equations, rows = the free coordinates) this is a few hundred operations on data it
// keeps between calls, where a QR-preconditioned two-sided SVD of dynamic size spends thousands on
// choosing its kernels (callgrind on BM_TramwaySimulation).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mbsopt {

class OneSidedJacobiSvd {
 public:
  /// Rotates until no pair of columns of A W is further from orthogonal than √rows · ε relative to
  /// the product of their norms (the test of LAPACK's xGESVJ), or kMaxSweeps sweeps. Columns whose
  /// norm is below ε ‖A‖_F are round-off of a zero column: no rotation involves them. Allocates
  /// nothing once its buffers have A's size.
  void compute(const Eigen::MatrixXd& a);
  /// The same decomposition of a matrix near the last one, started from the last W instead of I: the
  /// columns of A W are then nearly orthogonal already, and the sweeps, which converge quadratically,
  /// take about 4 instead of 6, the last one rotating nothing (Andrews' squeezer from one Newmark step
  /// to the next). Rotations on rotations lose W's orthogonality by about 3 ε per call (200 ε after
  /// 60, tests/1-linalg/test_one_sided_jacobi.cpp), so every kWarmStartsBeforeCold-th call, and any call whose
  /// A has other sizes than the last, starts from I as compute() does. With `orthogonality` > 0 the
  /// sweeps stop once no pair of columns is further from orthogonal than that, relative to the product
  /// of their norms, instead of √rows · ε: W stays orthogonal and A W = X Σ exact to round-off, only
  /// X's columns are then orthogonal to that tolerance (one sweep fewer at 1e-8, SvdPartition's
  /// kFastOrthogonality), and the last sweep, which would only confirm it, is skipped where the
  /// quadratic convergence of the sweeps already guarantees it (confirmedByConvergence).
  void update(const Eigen::MatrixXd& a, double orthogonality = 0.0);

  /// Σ: the column norms of A W in decreasing order, one per column of A; those beyond the rank of
  /// A are round-off (and beyond min(rows, cols) there are only such).
  const Eigen::VectorXd& singularValues() const { return sigma_; }
  /// A W with its columns in the order of singularValues(): mutually orthogonal, column j of norm σ_j.
  const Eigen::MatrixXd& orthogonalColumns() const { return columns_; }
  /// W, cols × cols, orthogonal, its columns in the same order.
  const Eigen::MatrixXd& rotations() const { return rotations_; }
  /// The minimum-norm least-squares solution of A x = b, x = W Σ⁺ Xᵀ b, with the singular values
  /// at or below `relative_threshold` σ₀ taken as zero. Allocates nothing once x and `work` have
  /// their sizes.
  void solveLeastSquares(const Eigen::VectorXd& b, double relative_threshold, Eigen::VectorXd& x,
                         Eigen::VectorXd& work) const;
  /// The sweeps the last compute() took, the last one rotating nothing unless kMaxSweeps was reached.
  int sweeps() const { return sweeps_; }

  static constexpr int kMaxSweeps = 30;
  /// How far below the orthogonality asked for the convergence bound must put the next sweep's
  /// largest product before that sweep is skipped: the bound holds up to a factor of the order of
  /// the number of columns.
  static constexpr double kConvergenceSafety = 10.0;
  static constexpr int kWarmStartsBeforeCold = 16;

 private:
  Eigen::MatrixXd work_columns_, work_rotations_, columns_, rotations_;
  Eigen::VectorXd squared_norms_, sigma_;
  std::vector<Eigen::Index> order_;
  int sweeps_ = 0;
  int warm_starts_ = 0;  ///< update()s since W last started from I
  /// A and W = I into the work buffers.
  void startFromIdentity(const Eigen::MatrixXd& a);
  /// The sweeps to `orthogonality` (0: √rows · ε).
  void rotateToOrthogonal(double orthogonality);
  /// After a sweep whose largest rotated γ²/(αβ) was `largest`: whether the next is known to find every
  /// pair within `orthogonality` without being made: kConvergenceSafety · μ²/g ≤ τ (see the .cpp).
  bool confirmedByConvergence(double largest, double orthogonality, double negligible_squared) const;
};

}  // namespace mbsopt
