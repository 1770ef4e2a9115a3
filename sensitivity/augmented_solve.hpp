// The augmented systems of the exact gradient methods, solved through the SVD partition (43)-(48)
// the integrator uses, so redundant closure equations drop out the same way:
//   X = L(top, bottom):  [J Bᵀ; B 0][X; Y] = [top; bottom]   (the X part, minimum-norm Y),
// and its transpose, for the adjoint: the row vectors (t̄, b̄) with x̄ X = t̄ top + b̄ bottom for all
// (top, bottom), which solve [Jᵀ Bᵀ; B 0][t̄ᵀ; b̄ᵀ] = [x̄ᵀ; 0].
#pragma once

#include <Eigen/Core>

namespace mbsopt {

/// Columns of X, one per column of top (n × p) and bottom (m × p); B may have no rows.
Eigen::MatrixXd solveAugmented(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& top,
                               const Eigen::MatrixXd& bottom, double threshold);

/// Rows of t̄ (r × n) and b̄ (r × m), one per row of x̄ (r × n).
void solveAugmentedTransposed(const Eigen::MatrixXd& J, const Eigen::MatrixXd& B, const Eigen::MatrixXd& xbar,
                              double threshold, Eigen::MatrixXd& tbar, Eigen::MatrixXd& bbar);

}  // namespace mbsopt
