#include "dynamics/svd_partition.hpp"
#include <algorithm>
#include <cmath>

namespace mbsopt {

namespace {

/// ‖x‖₁ of column j of (LU)⁻¹, i.e. of the solution of LUx = e_j by forward (unit L) and back
/// substitution on the packed factors `lu`; x is the buffer.
double inverseColumnOneNorm(const Eigen::MatrixXd& lu, Eigen::Index j, Eigen::VectorXd& x) {
  const Eigen::Index n = lu.rows();
  x.setUnit(n, j);
  for (Eigen::Index i = j + 1; i < n; ++i) x[i] -= lu.row(i).segment(j, i - j).dot(x.segment(j, i - j));
  for (Eigen::Index i = n; i-- > 0;) x[i] = (x[i] - lu.row(i).tail(n - 1 - i).dot(x.tail(n - 1 - i))) / lu(i, i);
  return x.lpNorm<1>();
}

}  // namespace

void SvdPartition::setConstraintJacobian(const Eigen::MatrixXd& B) {
  const Eigen::Index n = B.cols();
  if (B.rows() == 0) {
    rank_ = 0;
    singular_values_.resize(0);
    u1_.resize(0, 0);
    v1_.resize(n, 0);
    v2_ = Eigen::MatrixXd::Identity(n, n);
    inverse_s1_.resize(0);
    return;
  }
  svd_.compute(B, Eigen::ComputeFullU | Eigen::ComputeFullV);  // (43)
  singular_values_ = svd_.singularValues();
  const double largest = singular_values_.size() > 0 ? singular_values_[0] : 0.0;
  rank_ = 0;
  while (rank_ < singular_values_.size() && singular_values_[rank_] > threshold_ * largest && largest > 0.0) ++rank_;
  u1_ = svd_.matrixU().leftCols(rank_);
  v1_ = svd_.matrixV().leftCols(rank_);
  v2_ = svd_.matrixV().rightCols(n - rank_);
  inverse_s1_ = singular_values_.head(rank_).cwiseInverse();
  x_r_.resize(rank_);
}

bool SvdPartition::setIterationMatrix(const Eigen::MatrixXd& J) {
  J_ = J;
  if (v2_.cols() == 0) return true;
  j_v2_.noalias() = J * v2_;
  reduced_matrix_.noalias() = v2_.transpose() * j_v2_;
  reduced_.compute(reduced_matrix_);
  const double reciprocal_condition = reducedReciprocalCondition();
  return reciprocal_condition > 1e-13 && std::isfinite(reciprocal_condition);
}

double SvdPartition::reducedReciprocalCondition() const {
  // 1 / (‖A‖₁ ‖A⁻¹‖₁), exact (Eigen's estimator rcond() allocates on every call; these matrices are
  // small). With PA = LU, A⁻¹ = U⁻¹L⁻¹P: P only reorders the columns, so ‖A⁻¹‖₁ = ‖U⁻¹L⁻¹‖₁.
  const Eigen::MatrixXd& lu = reduced_.matrixLU();
  double inverse_norm = 0.0;
  for (Eigen::Index j = 0; j < lu.cols(); ++j) {
    const double column_norm = inverseColumnOneNorm(lu, j, x_n_);
    if (!std::isfinite(column_norm)) return 0.0;
    inverse_norm = std::max(inverse_norm, column_norm);
  }
  return 1.0 / (reduced_matrix_.cwiseAbs().colwise().sum().maxCoeff() * inverse_norm);
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
    x_n_ = reduced_.solve(reduced_rhs_);  // not in place: that would allocate a permutation mask
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
