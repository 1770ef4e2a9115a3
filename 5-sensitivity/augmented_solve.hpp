// The augmented systems of the exact gradient methods, solved through the SVD partition (43)-(48)
// the integrator uses, so redundant closure equations drop out the same way:
//   X = L(top, bottom):  [J Bᵀ; B 0][X; Y] = [top; bottom]   (the X part, minimum-norm Y),
// and its transpose, for the adjoint: the row vectors (t̄, b̄) with x̄ X = t̄ top + b̄ bottom for all
// (top, bottom), which solve [Jᵀ Bᵀ; B 0][t̄ᵀ; b̄ᵀ] = [x̄ᵀ; 0].
#pragma once

#include <Eigen/Core>

#include "mbsopt/algorithms/svd_partition.hpp"

namespace mbsopt {

/// The systems of one step: B's SVD once, then one factorisation per matrix J (a step solves with
/// M twice and with the iteration matrix once, all at the same B).
class AugmentedSolver {
 public:
  /// Without B yet: setConstraintJacobian before anything else. A solver kept from step to step
  /// reuses its buffers (no allocation once their sizes are reached).
  explicit AugmentedSolver(double threshold);
  /// B may have no rows.
  AugmentedSolver(const Eigen::MatrixXd& B, double threshold);
  /// B's SVD, for the steps of another time point; forgets the factored matrix.
  void setConstraintJacobian(const Eigen::MatrixXd& B);
  /// B's SVD as `partition` holds it (SvdPartition::copyConstraintFactors), the same to the bit as
  /// setConstraintJacobian(B) at its threshold; forgets the factored matrix.
  void setConstraintPartition(const SvdPartition& partition);

  /// B's partition and the symmetric J = Jᵀ it factored last, for solve() and solveTransposed()
  /// alike: the same to the bit as setConstraintJacobian(B) and setMatrix(J) or
  /// setTransposedMatrix(J). The solves read `partition` where it is (nothing is copied): it must
  /// stay alive and unchanged until the next set… call.
  void setFactoredSymmetricMatrix(const SvdPartition& partition);
  /// Factors J for solve(); throws std::runtime_error when it is singular on B's null space.
  void setMatrix(const Eigen::MatrixXd& J);
  /// Factors Jᵀ for solveTransposed(); throws std::runtime_error when it is singular.
  void setTransposedMatrix(const Eigen::MatrixXd& J);

  /// Columns of X, one per column of top (n × p) and bottom (m × p). Needs setMatrix.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& top, const Eigen::MatrixXd& bottom) const;
  /// The same into X, reusing its storage; top and bottom may be expressions (copied before X is written).
  template <class Top, class Bottom>
  void solve(const Eigen::MatrixBase<Top>& top, const Eigen::MatrixBase<Bottom>& bottom, Eigen::MatrixXd& X) const {
    top_rhs_ = -top;  // the partition solves for −[r; g]
    bottom_rhs_ = -bottom;
    solveColumns(X, nullptr);
  }
  /// The same with the multipliers' part Y (m × p) too: the minimum-norm one, Y = (Bᵀ)⁺(top − J X).
  template <class Top, class Bottom>
  void solve(const Eigen::MatrixBase<Top>& top, const Eigen::MatrixBase<Bottom>& bottom, Eigen::MatrixXd& X,
             Eigen::MatrixXd& Y) const {
    top_rhs_ = -top;
    bottom_rhs_ = -bottom;
    solveColumns(X, &Y);
  }
  /// Rows of t̄ (r × n) and b̄ (r × m), one per row of x̄ (r × n). Needs setTransposedMatrix.
  void solveTransposed(const Eigen::MatrixXd& xbar, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar) const;
  /// The same with a seed ȳ (r × m) on the multipliers Y as solve() gives them: the rows (t̄, b̄)
  /// with x̄ X + ȳ Y = t̄ top + b̄ bottom. With w = ȳ (Bᵀ)⁺ (w = (B⁺ȳᵀ)ᵀ), ȳ Y = w top − w J X, so
  /// t̄ = w + t̄' and b̄ = b̄', (t̄', b̄') the transposed solve of x̄ − w J. Needs setTransposedMatrix.
  void solveTransposed(const Eigen::MatrixXd& xbar, const Eigen::MatrixXd& ybar, Eigen::MatrixXd& tbar,
                       Eigen::MatrixXd& bbar) const;

 private:
  enum class Factored { None, Matrix, Transposed, Symmetric };
  /// X (and Y, when given) from the right-hand sides in top_rhs_, bottom_rhs_ (negated: the
  /// partition solves for −[r; g]), all columns in one SvdPartition::solveColumns. Needs setMatrix.
  void solveColumns(Eigen::MatrixXd& X, Eigen::MatrixXd* Y) const;
  /// The partition the solves use: partition_, or the one of setFactoredSymmetricMatrix.
  const SvdPartition& factoredPartition() const { return symmetric_ ? *symmetric_ : partition_; }
  SvdPartition partition_;
  const SvdPartition* symmetric_ = nullptr;  ///< setFactoredSymmetricMatrix's, read in place
  Eigen::MatrixXd transposed_;  ///< Jᵀ for setTransposedMatrix
  mutable Eigen::MatrixXd top_rhs_, bottom_rhs_;  ///< the right-hand sides, negated (solveTransposed: no bottom)
  mutable Eigen::MatrixXd tbar_t_, bbar_t_;  ///< solveTransposed's results, transposed
  mutable Eigen::MatrixXd w_t_, shifted_xbar_;  ///< solveTransposed's (B⁺ȳᵀ) and x̄ − w J
  mutable Eigen::VectorXd column_, w_column_;
  Factored factored_ = Factored::None;
};

/// X = L(top, bottom) with a solver of its own.
Eigen::MatrixXd solveAugmented(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& top,
                               const Eigen::MatrixXd& bottom, double threshold);

/// (t̄, b̄) for x̄, and ȳ on the multipliers when `ybar` is given, with a solver of its own.
void solveAugmentedTransposed(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& xbar,
                              double threshold, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar,
                              const Eigen::MatrixXd* ybar = nullptr);

}  // namespace mbsopt
