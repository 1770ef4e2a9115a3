#include "mbsopt/algorithms/svd_partition.hpp"
#include <algorithm>
#include <cmath>

#include "mbsopt/linalg/dot_product.hpp"
#include "mbsopt/linalg/lu_factors.hpp"
#include "mbsopt/linalg/small_products.hpp"

namespace mbsopt {

void SvdPartition::setConstraintJacobian(const Eigen::MatrixXd& B) { partition(B, false); }

void SvdPartition::updateConstraintJacobian(const Eigen::MatrixXd& B) { partition(B, true); }

void SvdPartition::partition(const Eigen::MatrixXd& B, bool from_last) {
  const Eigen::Index m = B.rows(), n = B.cols();
  if (m == 0) {
    rank_ = 0;
    singular_values_.resize(0);
    u1_.resize(0, 0);
    v1_.resize(n, 0);
    v2_ = Eigen::MatrixXd::Identity(n, n);
    v2_stale_ = false;
    inverse_s1_.resize(0);
    x_r_.resize(0);
    return;
  }
  // (43) from the one-sided Jacobi SVD of Bᵀ: Bᵀ W = X Σ, so B = W Σ Xᵀ, U = W and V₁ the directions
  // of the first r columns of X Σ; V₂, an orthonormal basis of their complement, from the Householder
  // QR of V₁ (its last n − r columns of Q), kept as reflectors for setIterationMatrix.
  transposed_ = B.transpose();
  if (from_last) jacobi_.update(transposed_, kFastOrthogonality);
  else jacobi_.compute(transposed_);
  singular_values_ = jacobi_.singularValues().head(std::min(m, n));
  const double largest = singular_values_.size() > 0 ? singular_values_[0] : 0.0;  // none: no free coordinate
  rank_ = 0;
  while (rank_ < singular_values_.size() && singular_values_[rank_] > threshold_ * largest && largest > 0.0) ++rank_;
  u1_ = jacobi_.rotations().leftCols(rank_);
  inverse_s1_ = singular_values_.head(rank_).cwiseInverse();
  v1_ = jacobi_.orthogonalColumns().leftCols(rank_) * inverse_s1_.asDiagonal();
  complement_.compute(v1_);
  v2_stale_ = true;  // formed when a dense factorization or a caller asks for it: the range-space solves do without
  x_r_.resize(rank_);
}

const Eigen::MatrixXd& SvdPartition::freeDirections() const {
  if (v2_stale_) {
    complement_.complement(v2_);
    v2_stale_ = false;
  }
  return v2_;
}

bool SvdPartition::setIterationMatrix(const Eigen::MatrixXd& J) {
  inverse_ = nullptr;
  J_ = J;
  freeDirections();
  const Eigen::Index n = J.rows(), free = v2_.cols(), k = rank_;
  if (free == 0) return true;
  if (k == 0) {
    reduced_matrix_ = J;  // V₂ = I
  } else if (n <= kReflectorsFrom) {
    j_v2_.resize(n, free);
    reduced_matrix_.resize(free, free);
    multiply(J.data(), v2_.data(), j_v2_.data(), n, n, free, Accumulate::Assign);
    multiplyTransposed(v2_.data(), j_v2_.data(), reduced_matrix_.data(), free, n, free);
  } else {
    // V₂ᵀ J V₂, the last n − r rows and columns of Qᵀ J Q, by the r reflectors on either side.
    rotated_ = J;
    complement_.transformSimilar(rotated_);
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

bool SvdPartition::setIterationMatrix(const ArticulatedBodyFactorization& inverse) {
  inverse_ = &inverse;
  const Eigen::Index n = v1_.rows();
  inverse_v1_.resize(n, rank_);
  column_.resize(n);
  for (Eigen::Index j = 0; j < rank_; ++j) {
    column_ = v1_.col(j);
    inverse.solve(column_, work_);
    inverse_v1_.col(j) = work_;
  }
  reduced_matrix_.resize(rank_, rank_);
  multiplyTransposed(v1_.data(), inverse_v1_.data(), reduced_matrix_.data(), rank_, n, rank_);
  if (rank_ == 0) return true;
  schur_.compute(reduced_matrix_);
  if (schur_.info() != Eigen::Success) return false;
  // The squared pivots of the Cholesky factor bound the spread of the eigenvalues from within.
  const auto pivots = schur_.matrixLLT().diagonal().cwiseAbs2();
  return pivots.minCoeff() > kSingular * pivots.maxCoeff() && std::isfinite(pivots.maxCoeff());
}

void SvdPartition::rangeSpaceIncrement(const Eigen::VectorXd* r, Eigen::VectorXd& dx) const {
  // x_r is in place. ν = −(V₁ᵀM⁻¹V₁)⁻¹ (x_r + V₁ᵀ M⁻¹ r), Δx = −(M⁻¹ r + M⁻¹V₁ ν).
  const Eigen::Index n = v1_.rows();
  nu_ = x_r_;
  if (r) {
    inverse_->solve(*r, dx);
    multiplyTransposed(v1_.data(), dx.data(), work_.data(), rank_, n, 1);
    nu_ += work_.head(rank_);
  } else {
    dx.setZero(n);
  }
  if (rank_ > 0) {
    schur_.solveInPlace(nu_);
    nu_ = -nu_;
    multiply(inverse_v1_, nu_, dx, Accumulate::Add);
  }
  dx = -dx;
}

void SvdPartition::rangeCoordinates(const double* g, Eigen::Index p, double* x_r) const {
  multiplyTransposed(u1_.data(), g, x_r, rank_, u1_.rows(), p);
  for (Eigen::Index j = 0; j < p; ++j)
    for (Eigen::Index i = 0; i < rank_; ++i) x_r[i + j * rank_] *= -inverse_s1_[i];
}

void SvdPartition::partitionIncrement(const double* r, const double* x_r, Eigen::Index p, double* dx) const {
  const Eigen::Index n = v1_.rows(), free = v2_.cols();
  if (x_r)
    multiply(v1_.data(), x_r, dx, n, rank_, p, Accumulate::Assign);  // V₁ X_r (zero without constraints: V₁ is n × 0)
  else
    std::fill(dx, dx + n * p, 0.0);
  if (free == 0) return;
  work_block_.resize(n, p);
  if (r) std::copy(r, r + n * p, work_block_.data());
  if (x_r) multiply(J_.data(), dx, work_block_.data(), n, n, p, r ? Accumulate::Add : Accumulate::Assign);  // R + J V₁ X_r
  reduced_block_.resize(free, p);
  multiplyTransposed(v2_.data(), work_block_.data(), reduced_block_.data(), free, n, p);
  // X_n = −(V₂ᵀJV₂)⁻¹ V₂ᵀ(R + J V₁ X_r), added as dx −= V₂ (V₂ᵀJV₂)⁻¹ V₂ᵀ(…): the same bits, as negating
  // a right-hand side negates every operation of the solve exactly.
  x_n_block_.resize(free, p);
  luSolveColumns(reduced_, reduced_block_.data(), p, x_n_block_.data());
  multiply(v2_.data(), x_n_block_.data(), dx, n, free, p, Accumulate::Subtract);
}

void SvdPartition::partitionMultipliers(const double* r, const double* dx, Eigen::Index p, double* dmu) const {
  const Eigen::Index n = v1_.rows(), m = u1_.rows();
  work_block_.resize(n, p);
  std::copy(r, r + n * p, work_block_.data());
  multiply(J_.data(), dx, work_block_.data(), n, n, p, Accumulate::Add);  // R + J ΔX
  multiplier_block_.resize(rank_, p);
  multiplyTransposed(v1_.data(), work_block_.data(), multiplier_block_.data(), rank_, n, p);
  for (Eigen::Index j = 0; j < p; ++j)
    for (Eigen::Index i = 0; i < rank_; ++i) multiplier_block_(i, j) *= inverse_s1_[i];
  multiply(u1_.data(), multiplier_block_.data(), dmu, m, rank_, p, Accumulate::Assign);
  for (Eigen::Index i = 0; i < m * p; ++i) dmu[i] = -dmu[i];
}

void SvdPartition::increment(const Eigen::VectorXd* r, const Eigen::VectorXd& g, Eigen::VectorXd& dx) const {
  dx.resize(v1_.rows());
  x_r_.resize(rank_);
  rangeCoordinates(g.data(), 1, x_r_.data());
  if (inverse_) {
    work_.resize(v1_.rows());
    rangeSpaceIncrement(r, dx);
    return;
  }
  partitionIncrement(r ? r->data() : nullptr, x_r_.data(), 1, dx.data());
}

void SvdPartition::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& g, Eigen::VectorXd& dx,
                         Eigen::VectorXd& dmu) const {
  increment(&r, g, dx);
  dmu.resize(u1_.rows());
  if (inverse_) {  // Δμ = U₁ S₁⁻¹ ν
    for (Eigen::Index i = 0; i < rank_; ++i) x_r_[i] = nu_[i] * inverse_s1_[i];
    multiply(u1_, x_r_, dmu);
    return;
  }
  partitionMultipliers(r.data(), dx.data(), 1, dmu.data());
}

void SvdPartition::solveColumns(const Eigen::MatrixXd& R, const Eigen::MatrixXd& G, Eigen::MatrixXd& dx,
                                Eigen::MatrixXd* dmu) const {
  const Eigen::Index p = R.cols();
  dx.resize(v1_.rows(), p);
  if (dmu) dmu->resize(u1_.rows(), p);
  if (inverse_) {  // the range-space solves, a column at a time
    for (Eigen::Index j = 0; j < p; ++j) {
      column_r_ = R.col(j);
      column_g_ = G.col(j);
      if (dmu) {
        solve(column_r_, column_g_, column_dx_, column_dmu_);
        dmu->col(j) = column_dmu_;
      } else {
        increment(&column_r_, column_g_, column_dx_);
      }
      dx.col(j) = column_dx_;
    }
    return;
  }
  x_r_block_.resize(rank_, p);
  rangeCoordinates(G.data(), p, x_r_block_.data());
  partitionIncrement(R.data(), x_r_block_.data(), p, dx.data());
  if (dmu) partitionMultipliers(R.data(), dx.data(), p, dmu->data());
}

void SvdPartition::solveColumns(const Eigen::MatrixXd& R, Eigen::MatrixXd& dx, Eigen::MatrixXd& dmu) const {
  const Eigen::Index n = v1_.rows(), p = R.cols();
  if (inverse_) {  // the range-space solves take G as it is
    zero_block_.setZero(u1_.rows(), p);
    return solveColumns(R, zero_block_, dx, &dmu);
  }
  dx.resize(n, p);
  dmu.resize(u1_.rows(), p);
  partitionIncrement(R.data(), nullptr, p, dx.data());
  partitionMultipliers(R.data(), dx.data(), p, dmu.data());
}

void SvdPartition::project(const Eigen::VectorXd& g, Eigen::VectorXd& dx) const { increment(nullptr, g, dx); }

void SvdPartition::transposedPseudoInverse(const Eigen::VectorXd& w, Eigen::VectorXd& mu) const {
  multiplyTransposed(v1_, w, x_r_);
  for (Eigen::Index i = 0; i < rank_; ++i) x_r_[i] *= inverse_s1_[i];
  multiply(u1_, x_r_, mu);
}

void SvdPartition::pseudoInverse(const Eigen::VectorXd& c, Eigen::VectorXd& dx) const {
  dx.resize(v1_.rows());
  multiplyTransposed(u1_, c, x_r_);
  for (Eigen::Index i = 0; i < rank_; ++i) x_r_[i] *= inverse_s1_[i];
  multiply(v1_, x_r_, dx);
}

}  // namespace mbsopt
