#include "dynamics/svd_partition.hpp"
#include <cmath>

namespace mbsopt {

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
  if (v2_.cols() == 0) {
    rcond_ = 1.0;
    return true;
  }
  j_v2_.noalias() = J * v2_;
  reduced_matrix_.noalias() = v2_.transpose() * j_v2_;
  reduced_.compute(reduced_matrix_);
  rcond_ = reduced_.rcond();
  return rcond_ > 1e-13 && std::isfinite(rcond_);
}

void SvdPartition::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& g, Eigen::VectorXd& dx,
                         Eigen::VectorXd& dmu) const {
  x_r_.noalias() = u1_.transpose() * g;
  x_r_ = -(inverse_s1_.asDiagonal() * x_r_);
  dx.noalias() = v1_ * x_r_;
  if (v2_.cols() > 0) {
    work_ = r;
    work_.noalias() += J_ * dx;
    x_n_.noalias() = v2_.transpose() * work_;
    x_n_ = -x_n_;
    x_n_ = reduced_.solve(x_n_);
    dx.noalias() += v2_ * x_n_;
  }
  work_ = r;
  work_.noalias() += J_ * dx;
  x_r_.noalias() = v1_.transpose() * work_;
  x_r_ = inverse_s1_.asDiagonal() * x_r_;
  dmu.noalias() = u1_ * x_r_;
  dmu = -dmu;
}

void SvdPartition::pseudoInverse(const Eigen::VectorXd& c, Eigen::VectorXd& dx) const {
  x_r_.noalias() = u1_.transpose() * c;
  x_r_ = inverse_s1_.asDiagonal() * x_r_;
  dx.noalias() = v1_ * x_r_;
}

}  // namespace mbsopt
