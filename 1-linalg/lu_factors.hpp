// LU factors with partial pivoting, P A = L U, and the solves with them, by plain loops along the
// contiguous columns of L and U on raw pointers. For the few-by-few reduced matrices of a Newmark
// step, Eigen's PartialPivLU spends more time choosing and blocking its kernels than on the O(n³)
// and O(n²) arithmetic, and so do its dynamic-size vector expressions (callgrind and perf on
// BM_TramwaySimulation); these loops allocate nothing once sized and stay the textbook algorithms
// for the large chains, where the compiler vectorises their inner loops.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/linalg/dot_product.hpp"

namespace mbsopt {

/// P A = L U by Gaussian elimination with partial pivoting, right-looking (Golub and Van Loan,
/// "Matrix Computations", 4th ed., Algorithm 3.4.1; LAPACK's xGETF2): the pivot of column k is its
/// entry of largest magnitude on or below the diagonal, the first of equal ones. A zero pivot leaves
/// its column unscaled and the elimination goes on (a singular U), as in LAPACK; the solves then
/// give infinities, which the condition estimates report as singular.
class LuFactors {
 public:
  void compute(const Eigen::MatrixXd& a);
  /// L below the diagonal (its unit diagonal implied), U on and above.
  const Eigen::MatrixXd& matrixLU() const { return lu_; }
  /// Row k of P A is row rows()[k] of A.
  const std::vector<int>& rows() const { return rows_; }
  /// Factors compute() left (n × n, column-major, as matrixLU()) and their row order (n entries).
  void assign(const double* lu, const double* rows, Eigen::Index n);

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> rows_;
};

namespace detail {

/// luSolveColumns with the column count a constant when Columns > 0 (one column: the loops over the
/// columns vanish), the runtime `columns` when Columns = 0: the same operations in the same order.
template <int Columns>
inline void luSolveColumnsOf(const LuFactors& lu, const double* __restrict b, Eigen::Index columns,
                             double* __restrict x) {
  const Eigen::Index p = Columns > 0 ? Columns : columns;
  const Eigen::MatrixXd& f = lu.matrixLU();
  const Eigen::Index n = f.rows();
  const int* rows = lu.rows().data();
  for (Eigen::Index c = 0; c < p; ++c)
    for (Eigen::Index i = 0; i < n; ++i) x[i + c * n] = b[rows[i] + c * n];  // Y = P B
  for (Eigen::Index j = 0; j + 1 < n; ++j) {
    const double* l = f.data() + j * n;
    for (Eigen::Index c = 0; c < p; ++c) {
      double* y = x + c * n;
      const double yj = y[j];
      for (Eigen::Index i = j + 1; i < n; ++i) y[i] -= l[i] * yj;
    }
  }
  for (Eigen::Index j = n; j-- > 0;) {
    const double* u = f.data() + j * n;
    for (Eigen::Index c = 0; c < p; ++c) {
      double* y = x + c * n;
      const double yj = y[j] /= u[j];
      for (Eigen::Index i = 0; i < j; ++i) y[i] -= u[i] * yj;
    }
  }
}

}  // namespace detail

/// X = A⁻¹ B for the p columns of B (n × p, column-major) into X (n × p, not B's storage): L U X = P B,
/// forward with the unit lower triangle, then back with the upper one. Each column gets the
/// operations of a solve of its own in the same order; they are taken a row at a time across the
/// columns, so that the columns' divisions overlap instead of each waiting for the last.
inline void luSolveColumns(const LuFactors& lu, const double* b, Eigen::Index p, double* x) {
  if (p == 1) detail::luSolveColumnsOf<1>(lu, b, p, x);
  else detail::luSolveColumnsOf<0>(lu, b, p, x);
}

/// x = A⁻¹ b (luSolveColumns on one column).
inline void luSolve(const LuFactors& lu, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x.resize(lu.matrixLU().rows());
  luSolveColumns(lu, b.data(), 1, x.data());
}

/// x = A⁻ᵀ b: Aᵀ = Uᵀ Lᵀ P, so Uᵀ w = b forward, Lᵀ u = w backward (dot products down the columns of
/// U and L), then x = Pᵀ u. `w` is scratch.
inline void luSolveTransposed(const LuFactors& lu, const Eigen::VectorXd& b,
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
  const int* p = lu.rows().data();
  for (Eigen::Index i = 0; i < n; ++i) x[p[i]] = v[i];  // x = Pᵀ w
}

}  // namespace mbsopt
