#include "mbsopt/sensitivity/augmented_solve.hpp"

#include <stdexcept>

namespace mbsopt {

AugmentedSolver::AugmentedSolver(double threshold) : partition_(threshold) {}

AugmentedSolver::AugmentedSolver(const Eigen::MatrixXd& B, double threshold) : partition_(threshold) {
  setConstraintJacobian(B);
}

void AugmentedSolver::setConstraintJacobian(const Eigen::MatrixXd& B) {
  factored_ = Factored::None;
  symmetric_ = nullptr;
  partition_.setConstraintJacobian(B);
}

void AugmentedSolver::setConstraintPartition(const SvdPartition& partition) {
  factored_ = Factored::None;
  symmetric_ = nullptr;
  partition_.copyConstraintFactors(partition);
}

void AugmentedSolver::setFactoredSymmetricMatrix(const SvdPartition& partition) {
  symmetric_ = &partition;
  factored_ = Factored::Symmetric;
}

void AugmentedSolver::setMatrix(const Eigen::MatrixXd& J) {
  factored_ = Factored::None;
  symmetric_ = nullptr;
  if (!partition_.setIterationMatrix(J)) throw std::runtime_error("exact gradients: singular step matrix");
  factored_ = Factored::Matrix;
}

void AugmentedSolver::setTransposedMatrix(const Eigen::MatrixXd& J) {
  factored_ = Factored::None;
  symmetric_ = nullptr;
  transposed_ = J.transpose();
  if (!partition_.setIterationMatrix(transposed_)) throw std::runtime_error("exact gradients: singular step matrix");
  factored_ = Factored::Transposed;
}

Eigen::MatrixXd AugmentedSolver::solve(const Eigen::MatrixXd& top, const Eigen::MatrixXd& bottom) const {
  Eigen::MatrixXd X;
  solve(top, bottom, X);
  return X;
}

void AugmentedSolver::solveColumns(Eigen::MatrixXd& X, Eigen::MatrixXd* Y) const {
  if (factored_ != Factored::Matrix && factored_ != Factored::Symmetric)
    throw std::logic_error("AugmentedSolver::solve needs setMatrix");
  factoredPartition().solveColumns(top_rhs_, bottom_rhs_, X, Y);
}

void AugmentedSolver::solveTransposed(const Eigen::MatrixXd& xbar, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar) const {
  // With X = V₁S₁⁻¹U₁ᵀ bottom + V₂R⁻¹V₂ᵀ(top − J V₁S₁⁻¹U₁ᵀ bottom), R = V₂ᵀJV₂, the transpose is
  // t̄ = x̄ V₂R⁻¹V₂ᵀ and b̄ = (x̄ − t̄ J) V₁S₁⁻¹U₁ᵀ: exactly the partition's solution of the system
  // with Jᵀ, right-hand side [x̄ᵀ; 0], its Δx being t̄ᵀ and its minimum-norm Δμ being b̄ᵀ.
  if (factored_ != Factored::Transposed && factored_ != Factored::Symmetric)
    throw std::logic_error("AugmentedSolver::solveTransposed needs setTransposedMatrix");
  // Solved as the columns of the transposes, one per row of x̄, with a zero bottom.
  top_rhs_ = -xbar.transpose();
  factoredPartition().solveColumns(top_rhs_, tbar_t_, bbar_t_);
  tbar = tbar_t_.transpose();
  bbar = bbar_t_.transpose();
}

void AugmentedSolver::solveTransposed(const Eigen::MatrixXd& xbar, const Eigen::MatrixXd& ybar, Eigen::MatrixXd& tbar,
                                      Eigen::MatrixXd& bbar) const {
  if (factored_ != Factored::Transposed) throw std::logic_error("AugmentedSolver::solveTransposed(ȳ) needs setTransposedMatrix");
  const SvdPartition& partition = factoredPartition();
  w_t_.resize(xbar.cols(), ybar.rows());
  for (Eigen::Index r = 0; r < ybar.rows(); ++r) {
    column_ = ybar.row(r).transpose();
    partition.pseudoInverse(column_, w_column_);
    w_t_.col(r) = w_column_;
  }
  shifted_xbar_.noalias() = xbar - (transposed_ * w_t_).transpose();  // x̄ − w J, (w J)ᵀ = Jᵀ wᵀ
  solveTransposed(shifted_xbar_, tbar, bbar);
  tbar += w_t_.transpose();
}

Eigen::MatrixXd solveAugmented(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& top,
                               const Eigen::MatrixXd& bottom, double threshold) {
  AugmentedSolver solver(B, threshold);
  solver.setMatrix(J);
  return solver.solve(top, bottom);
}

void solveAugmentedTransposed(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& xbar,
                              double threshold, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar,
                              const Eigen::MatrixXd* ybar) {
  AugmentedSolver solver(B, threshold);
  solver.setTransposedMatrix(J);
  if (ybar) solver.solveTransposed(xbar, *ybar, tbar, bbar);
  else solver.solveTransposed(xbar, tbar, bbar);
}

}  // namespace mbsopt
