// Solves with the factors of Eigen's PartialPivLU (PA = LU) by plain substitution along the
// contiguous columns of L and U, on raw pointers. For the few-by-few reduced matrices of a Newmark
// step, Eigen's solve() spends more time choosing and blocking its kernels than on the O(n²)
// arithmetic, and so do its dynamic-size vector expressions (callgrind and perf on
// BM_TramwaySimulation); these loops allocate nothing and stay O(n²) for the large chains, where the
// compiler vectorises their inner loops.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace mbsopt {

/// Σ aₖbₖ over n contiguous entries. A plain loop for a few entries; from 16 on Eigen's dot, whose
/// SIMD partial sums the compiler may not form itself (it must keep a loop's order of additions).
inline double dotProduct(const double* a, const double* b, Eigen::Index n) {
  if (n >= 16) return Eigen::Map<const Eigen::VectorXd>(a, n).dot(Eigen::Map<const Eigen::VectorXd>(b, n));
  double sum = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) sum += a[k] * b[k];
  return sum;
}

/// x = A⁻¹ b: L U x = P b, forward with the unit lower triangle, then back with the upper one.
inline void luSolve(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const Eigen::MatrixXd& f = lu.matrixLU();
  const Eigen::Index n = f.rows();
  x.resize(n);
  const int* p = lu.permutationP().indices().data();
  double* y = x.data();
  for (Eigen::Index i = 0; i < n; ++i) y[p[i]] = b[i];  // y = P b
  for (Eigen::Index j = 0; j + 1 < n; ++j) {
    const double* l = f.data() + j * n;
    const double yj = y[j];
    for (Eigen::Index i = j + 1; i < n; ++i) y[i] -= l[i] * yj;
  }
  for (Eigen::Index j = n; j-- > 0;) {
    const double* u = f.data() + j * n;
    const double yj = y[j] /= u[j];
    for (Eigen::Index i = 0; i < j; ++i) y[i] -= u[i] * yj;
  }
}

/// x = A⁻ᵀ b: Aᵀ = Uᵀ Lᵀ P, so Uᵀ w = b forward, Lᵀ u = w backward (dot products down the columns of
/// U and L), then x = Pᵀ u. `w` is scratch.
inline void luSolveTransposed(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& b,
                              Eigen::VectorXd& w, Eigen::VectorXd& x) {
  const Eigen::MatrixXd& f = lu.matrixLU();
  const Eigen::Index n = f.rows();
  w = b;
  double* v = w.data();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* u = f.data() + i * n;
    v[i] = (v[i] - dotProduct(u, v, i)) / u[i];
  }
  for (Eigen::Index i = n - 1; i-- > 0;) {
    const double* l = f.data() + i * n;
    v[i] -= dotProduct(l + i + 1, v + i + 1, n - 1 - i);
  }
  x.resize(n);
  const int* p = lu.permutationP().indices().data();
  for (Eigen::Index i = 0; i < n; ++i) x[i] = v[p[i]];  // x = Pᵀ w
}

}  // namespace mbsopt
