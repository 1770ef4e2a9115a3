#include "sensitivity/augmented_solve.hpp"

#include <stdexcept>

#include "dynamics/svd_partition.hpp"

namespace mbsopt {

namespace {

SvdPartition factor(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, double threshold) {
  SvdPartition partition(threshold);
  partition.setConstraintJacobian(B);
  if (!partition.setIterationMatrix(J)) throw std::runtime_error("exact gradients: singular step matrix");
  return partition;
}

}  // namespace

Eigen::MatrixXd solveAugmented(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& top,
                               const Eigen::MatrixXd& bottom, double threshold) {
  const SvdPartition partition = factor(J, B, threshold);
  Eigen::MatrixXd X(top.rows(), top.cols());
  Eigen::VectorXd dx, dmu;
  for (Eigen::Index c = 0; c < top.cols(); ++c) {
    partition.solve(-top.col(c), -bottom.col(c), dx, dmu);  // it solves for −[r; g]
    X.col(c) = dx;
  }
  return X;
}

void solveAugmentedTransposed(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& xbar,
                              double threshold, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar) {
  // With X = V₁S₁⁻¹U₁ᵀ bottom + V₂R⁻¹V₂ᵀ(top − J V₁S₁⁻¹U₁ᵀ bottom), R = V₂ᵀJV₂, the transpose is
  // t̄ = x̄ V₂R⁻¹V₂ᵀ and b̄ = (x̄ − t̄ J) V₁S₁⁻¹U₁ᵀ: exactly the partition's solution of the system
  // with Jᵀ, right-hand side [x̄ᵀ; 0], its Δx being t̄ᵀ and its minimum-norm Δμ being b̄ᵀ.
  const SvdPartition partition = factor(J.transpose(), B, threshold);
  // Filled by columns of the transposes: a row of bbar without constraints (B.rows() = 0) would be
  // an offset from Eigen's null data pointer.
  Eigen::MatrixXd tbar_t(xbar.cols(), xbar.rows()), bbar_t(B.rows(), xbar.rows());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(B.rows());
  Eigen::VectorXd dx, dmu;
  for (Eigen::Index r = 0; r < xbar.rows(); ++r) {
    partition.solve(-xbar.row(r).transpose(), zero, dx, dmu);
    tbar_t.col(r) = dx;
    bbar_t.col(r) = dmu;
  }
  tbar = tbar_t.transpose();
  bbar = bbar_t.transpose();
}

}  // namespace mbsopt
