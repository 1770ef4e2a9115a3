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
    x_r_.resize(0);
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

namespace {

// The products of the partition, on raw column-major data: the matrices have a few rows and
// columns, where Eigen's dynamic-size product kernels and expressions spend more on choosing and
// peeling their loops than on the arithmetic (perf on BM_TramwaySimulation); for the large chains
// the inner loops run down contiguous columns, which the compiler vectorises.

/// C = A B (A rows × inner, B inner × cols), or C += A B when `accumulate`.
void multiply(const double* __restrict a, const double* __restrict b, double* __restrict c, Eigen::Index rows, Eigen::Index inner, Eigen::Index cols,
              bool accumulate) {
  for (Eigen::Index j = 0; j < cols; ++j) {
    double* cj = c + j * rows;
    if (!accumulate) std::fill(cj, cj + rows, 0.0);
    for (Eigen::Index k = 0; k < inner; ++k) {
      const double* ak = a + k * rows;
      const double bkj = b[k + j * inner];
      for (Eigen::Index i = 0; i < rows; ++i) cj[i] += ak[i] * bkj;
    }
  }
}

/// C = Aᵀ B (A inner × rows, B inner × cols): a dot product down two columns per coefficient.
void multiplyTransposed(const double* __restrict a, const double* __restrict b, double* __restrict c, Eigen::Index rows, Eigen::Index inner,
                        Eigen::Index cols) {
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) c[i + j * rows] = dotProduct(a + i * inner, b + j * inner, inner);
}

/// y = A x, or y += A x when `accumulate`.
void multiply(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, Eigen::VectorXd& y, bool accumulate) {
  multiply(a.data(), x.data(), y.data(), a.rows(), a.cols(), 1, accumulate);
}

/// y = Aᵀ x.
void multiplyTransposed(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  multiplyTransposed(a.data(), x.data(), y.data(), a.cols(), a.rows(), 1);
}

}  // namespace

bool SvdPartition::setIterationMatrix(const Eigen::MatrixXd& J) {
  J_ = J;
  const Eigen::Index n = J.rows(), free = v2_.cols(), k = reflectors_;
  if (free == 0) return true;
  if (k == 0) {
    reduced_matrix_ = J;  // V₂ = I
  } else if (n <= kReflectorsFrom) {
    j_v2_.resize(n, free);
    reduced_matrix_.resize(free, free);
    multiply(J.data(), v2_.data(), j_v2_.data(), n, n, free, false);
    multiplyTransposed(v2_.data(), j_v2_.data(), reduced_matrix_.data(), free, n, free);
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
  // Hager's estimate is never below the true reciprocal condition, which is never below the
  // triangles' bound: a bound above the threshold (with a factor 2 for round-off) decides as the
  // estimate would, at the cost of one solve instead of five or more.
  if (reduced_matrix_.rows() <= kBoundUpTo &&
      reciprocalConditionLowerBound(reduced_matrix_, reduced_, bound_scratch_) > 2.0 * kSingular)
    return true;
  const double reciprocal_condition = condition_.reciprocalCondition(reduced_matrix_, reduced_);
  return reciprocal_condition > kSingular && std::isfinite(reciprocal_condition);
}

void SvdPartition::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& g, Eigen::VectorXd& dx,
                         Eigen::VectorXd& dmu) const {
  const Eigen::Index n = v1_.rows();
  dx.resize(n);
  dmu.resize(u1_.rows());
  work_.resize(n);
  multiplyTransposed(u1_, g, x_r_);  // x_r = −S₁⁻¹ U₁ᵀ g
  for (Eigen::Index i = 0; i < rank_; ++i) x_r_[i] *= -inverse_s1_[i];
  multiply(v1_, x_r_, dx, false);  // V₁ x_r (zero without constraints: V₁ is n × 0)
  if (v2_.cols() > 0) {
    work_ = r;
    multiply(J_, dx, work_, true);  // r + J V₁ x_r
    reduced_rhs_.resize(v2_.cols());
    multiplyTransposed(v2_, work_, reduced_rhs_);
    reduced_rhs_ = -reduced_rhs_;
    luSolve(reduced_, reduced_rhs_, x_n_);
    multiply(v2_, x_n_, dx, true);
  }
  work_ = r;
  multiply(J_, dx, work_, true);  // r + J Δx
  multiplyTransposed(v1_, work_, x_r_);
  for (Eigen::Index i = 0; i < rank_; ++i) x_r_[i] *= inverse_s1_[i];
  multiply(u1_, x_r_, dmu, false);
  dmu = -dmu;
}

void SvdPartition::pseudoInverse(const Eigen::VectorXd& c, Eigen::VectorXd& dx) const {
  dx.resize(v1_.rows());
  multiplyTransposed(u1_, c, x_r_);
  for (Eigen::Index i = 0; i < rank_; ++i) x_r_[i] *= inverse_s1_[i];
  multiply(v1_, x_r_, dx, false);
}

}  // namespace mbsopt
