#include "dynamics/svd_partition.hpp"
#include <algorithm>
#include <cmath>

#include "dynamics/lu_solve.hpp"

namespace mbsopt {

void SvdPartition::setConstraintJacobian(const Eigen::MatrixXd& B) {
  const Eigen::Index m = B.rows(), n = B.cols();
  reflectors_ = 0;
  if (m == 0) {
    rank_ = 0;
    singular_values_.resize(0);
    u1_.resize(0, 0);
    v1_.resize(n, 0);
    v2_ = Eigen::MatrixXd::Identity(n, n);
    inverse_s1_.resize(0);
    return;
  }
  // (43) in two stages, as Eigen's JacobiSVD does for a wide matrix: Bᵀ P = Q R by Householder QR
  // with column pivoting (k = min(m, n) reflectors, R = [R_k; 0]), so B = (P R_kᵀ) Q_kᵀ; then the
  // SVD of the small m × k matrix P R_kᵀ = Ũ S W̃ᵀ gives B = Ũ S (Q_k W̃)ᵀ: U = Ũ, and in the
  // coordinates of Q the right singular vectors are W̃ on the first k and the identity on the rest.
  // Keeping Q as its reflectors lets setIterationMatrix form V₂ᵀ J V₂ in O(n² k), not O(n³).
  qr_.compute(B.transpose());
  reflectors_ = std::min(m, n);
  small_ = qr_.matrixQR().topRows(reflectors_).triangularView<Eigen::Upper>().transpose();
  permuted_small_.noalias() = qr_.colsPermutation() * small_;
  small_svd_.compute(permuted_small_, Eigen::ComputeFullU | Eigen::ComputeFullV);
  singular_values_ = small_svd_.singularValues();
  const double largest = singular_values_.size() > 0 ? singular_values_[0] : 0.0;
  rank_ = 0;
  while (rank_ < singular_values_.size() && singular_values_[rank_] > threshold_ * largest && largest > 0.0) ++rank_;
  u1_ = small_svd_.matrixU().leftCols(rank_);
  v_.setIdentity(n, n);
  v_.topLeftCorner(reflectors_, reflectors_) = small_svd_.matrixV();
  qr_.householderQ().applyThisOnTheLeft(v_, householder_workspace_);  // V = Q diag(W̃, I)
  v1_ = v_.leftCols(rank_);
  v2_ = v_.rightCols(n - rank_);
  inverse_s1_ = singular_values_.head(rank_).cwiseInverse();
  x_r_.resize(rank_);
}

bool SvdPartition::setIterationMatrix(const Eigen::MatrixXd& J) {
  J_ = J;
  const Eigen::Index free = v2_.cols(), k = reflectors_;
  if (free == 0) return true;
  if (k == 0) {
    reduced_matrix_ = J;  // V₂ = I
  } else if (J.rows() <= kReflectorsFrom) {
    j_v2_.noalias() = J.lazyProduct(v2_);
    reduced_matrix_.noalias() = v2_.transpose().lazyProduct(j_v2_);
  } else {
    // V₂ᵀ J V₂, the last n − rank rows and columns of Vᵀ J V with V = Q diag(W̃, I): T = Qᵀ J Q by the
    // k reflectors on either side, then W̃ on the first k rows and columns of T.
    rotated_ = J;
    qr_.householderQ().transpose().applyThisOnTheLeft(rotated_, householder_workspace_);
    qr_.householderQ().applyThisOnTheRight(rotated_, householder_workspace_);
    rows_k_.noalias() = small_svd_.matrixV().transpose() * rotated_.topRows(k);
    rotated_.topRows(k) = rows_k_;
    columns_k_.noalias() = rotated_.leftCols(k) * small_svd_.matrixV();
    rotated_.leftCols(k) = columns_k_;
    reduced_matrix_ = rotated_.bottomRightCorner(free, free);
  }
  reduced_.compute(reduced_matrix_);
  const double reciprocal_condition = condition_.reciprocalCondition(reduced_matrix_, reduced_);
  return reciprocal_condition > 1e-13 && std::isfinite(reciprocal_condition);
}

// The products below use lazyProduct (coefficient by coefficient): the matrices have a few rows
// and columns, where the blocked matrix-vector kernels cost more than the arithmetic.

namespace {

/// dx = V₁ x_r. Without constraints (rank 0) V₁ is n × 0 and Eigen's null data pointer: each
/// coefficient of the lazy product would offset it by its row (undefined behaviour), so zero.
void rangeStep(const Eigen::MatrixXd& v1, const Eigen::VectorXd& x_r, Eigen::VectorXd& dx) {
  if (v1.cols() == 0) dx.setZero(v1.rows());
  else dx.noalias() = v1.lazyProduct(x_r);
}

}  // namespace

void SvdPartition::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& g, Eigen::VectorXd& dx,
                         Eigen::VectorXd& dmu) const {
  x_r_.noalias() = -(inverse_s1_.asDiagonal() * u1_.transpose().lazyProduct(g));
  rangeStep(v1_, x_r_, dx);
  if (v2_.cols() > 0) {
    work_.noalias() = r + J_.lazyProduct(dx);
    reduced_rhs_.noalias() = -v2_.transpose().lazyProduct(work_);
    luSolve(reduced_, reduced_rhs_, x_n_);
    dx.noalias() += v2_.lazyProduct(x_n_);
  }
  work_.noalias() = r + J_.lazyProduct(dx);
  x_r_.noalias() = inverse_s1_.asDiagonal() * v1_.transpose().lazyProduct(work_);
  dmu.noalias() = -u1_.lazyProduct(x_r_);
}

void SvdPartition::pseudoInverse(const Eigen::VectorXd& c, Eigen::VectorXd& dx) const {
  x_r_.noalias() = inverse_s1_.asDiagonal() * u1_.transpose().lazyProduct(c);
  rangeStep(v1_, x_r_, dx);
}

}  // namespace mbsopt
