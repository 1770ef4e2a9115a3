// Solves with the factors of Eigen's PartialPivLU (PA = LU) by plain substitution along the
// contiguous columns of L and U. For the few-by-few reduced matrices of a Newmark step, Eigen's
// solve() spends more time choosing and blocking its kernels than on the O(n²) arithmetic (callgrind
// on BM_TramwaySimulation); these loops allocate nothing and stay O(n²) for the large chains.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace mbsopt {

/// x = A⁻¹ b: L U x = P b, forward with the unit lower triangle, then back with the upper one.
inline void luSolve(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const Eigen::MatrixXd& f = lu.matrixLU();
  const Eigen::Index n = f.rows();
  x.noalias() = lu.permutationP() * b;  // into another vector: no permutation mask is allocated
  for (Eigen::Index j = 0; j + 1 < n; ++j) x.tail(n - 1 - j) -= f.col(j).tail(n - 1 - j) * x[j];
  for (Eigen::Index j = n; j-- > 0;) {
    x[j] /= f(j, j);
    x.head(j) -= f.col(j).head(j) * x[j];
  }
}

/// x = A⁻ᵀ b: Aᵀ = Uᵀ Lᵀ P, so Uᵀ w = b forward, Lᵀ u = w backward (dot products down the columns of
/// U and L), then x = Pᵀ u. `w` is scratch.
inline void luSolveTransposed(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& b,
                              Eigen::VectorXd& w, Eigen::VectorXd& x) {
  const Eigen::MatrixXd& f = lu.matrixLU();
  const Eigen::Index n = f.rows();
  w = b;
  for (Eigen::Index i = 0; i < n; ++i) w[i] = (w[i] - f.col(i).head(i).dot(w.head(i))) / f(i, i);
  for (Eigen::Index i = n - 1; i-- > 0;) w[i] -= f.col(i).tail(n - 1 - i).dot(w.tail(n - 1 - i));
  x.noalias() = lu.permutationP().transpose() * w;
}

}  // namespace mbsopt
