#include "sensitivity/augmented_solve.hpp"

#include <stdexcept>

namespace mbsopt {

AugmentedSolver::AugmentedSolver(double threshold) : partition_(threshold) {}

AugmentedSolver::AugmentedSolver(const Eigen::MatrixXd& B, double threshold) : partition_(threshold) {
  setConstraintJacobian(B);
}

void AugmentedSolver::setConstraintJacobian(const Eigen::MatrixXd& B) {
  factored_ = Factored::None;
  constraints_ = B.rows();
  partition_.setConstraintJacobian(B);
}

void AugmentedSolver::setMatrix(const Eigen::MatrixXd& J) {
  factored_ = Factored::None;
  if (!partition_.setIterationMatrix(J)) throw std::runtime_error("exact gradients: singular step matrix");
  factored_ = Factored::Matrix;
}

void AugmentedSolver::setTransposedMatrix(const Eigen::MatrixXd& J) {
  factored_ = Factored::None;
  transposed_ = J.transpose();
  if (!partition_.setIterationMatrix(transposed_)) throw std::runtime_error("exact gradients: singular step matrix");
  factored_ = Factored::Transposed;
}

Eigen::MatrixXd AugmentedSolver::solve(const Eigen::MatrixXd& top, const Eigen::MatrixXd& bottom) const {
  Eigen::MatrixXd X;
  solve(top, bottom, X);
  return X;
}

void AugmentedSolver::solveColumn(Eigen::MatrixXd& X, Eigen::Index c) const {
  if (factored_ != Factored::Matrix) throw std::logic_error("AugmentedSolver::solve needs setMatrix");
  partition_.solve(top_rhs_, bottom_rhs_, dx_, dmu_);  // it solves for −[r; g]
  X.col(c) = dx_;
}

void AugmentedSolver::solveTransposed(const Eigen::MatrixXd& xbar, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar) const {
  // With X = V₁S₁⁻¹U₁ᵀ bottom + V₂R⁻¹V₂ᵀ(top − J V₁S₁⁻¹U₁ᵀ bottom), R = V₂ᵀJV₂, the transpose is
  // t̄ = x̄ V₂R⁻¹V₂ᵀ and b̄ = (x̄ − t̄ J) V₁S₁⁻¹U₁ᵀ: exactly the partition's solution of the system
  // with Jᵀ, right-hand side [x̄ᵀ; 0], its Δx being t̄ᵀ and its minimum-norm Δμ being b̄ᵀ.
  if (factored_ != Factored::Transposed)
    throw std::logic_error("AugmentedSolver::solveTransposed needs setTransposedMatrix");
  // Filled by columns of the transposes: a row of bbar without constraints (B.rows() = 0) would be
  // an offset from Eigen's null data pointer.
  tbar_t_.resize(xbar.cols(), xbar.rows());
  bbar_t_.resize(constraints_, xbar.rows());
  bottom_rhs_.setZero(constraints_);
  for (Eigen::Index r = 0; r < xbar.rows(); ++r) {
    top_rhs_ = -xbar.row(r).transpose();
    partition_.solve(top_rhs_, bottom_rhs_, dx_, dmu_);
    tbar_t_.col(r) = dx_;
    bbar_t_.col(r) = dmu_;
  }
  tbar = tbar_t_.transpose();
  bbar = bbar_t_.transpose();
}

Eigen::MatrixXd solveAugmented(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& top,
                               const Eigen::MatrixXd& bottom, double threshold) {
  AugmentedSolver solver(B, threshold);
  solver.setMatrix(J);
  return solver.solve(top, bottom);
}

void solveAugmentedTransposed(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& xbar,
                              double threshold, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar) {
  AugmentedSolver solver(B, threshold);
  solver.setTransposedMatrix(J);
  solver.solveTransposed(xbar, tbar, bbar);
}

}  // namespace mbsopt
