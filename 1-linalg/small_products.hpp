// Products of small column-major matrices: the SVD partition's (the Newmark step's solves) and the
// exact gradients' sweeps (a handful of coordinates, closure rows, design variables or active
// constraints), where Eigen's dynamic-size product kernels and expressions spend more on choosing
// and peeling their loops than on the arithmetic (perf on BM_TramwaySimulation and
// BM_TramwayGradientAdjoint). For large chains the inner loops run down contiguous columns, which
// the compiler vectorises.
#pragma once

#include <Eigen/Core>
#include <cassert>

#include "mbsopt/linalg/dot_product.hpp"

namespace mbsopt {

/// What a product does with the matrix it writes: C = A B, C += A B or C −= A B.
enum class Accumulate { Assign, Add, Subtract };

namespace detail {

/// multiply() with the row count a constant when Rows > 0 (its inner loops unrolled), the runtime
/// `rows` when Rows = 0: the same operations in the same order either way.
template <int Rows, Accumulate Mode>
inline void multiplyRows(const double* __restrict a, const double* __restrict b, double* __restrict c,
                         Eigen::Index runtime_rows, Eigen::Index inner, Eigen::Index cols) {
  const Eigen::Index rows = Rows > 0 ? Rows : runtime_rows;
  for (Eigen::Index j = 0; j < cols; ++j) {
    double* cj = c + j * rows;
    if constexpr (Mode == Accumulate::Assign)
      for (Eigen::Index i = 0; i < rows; ++i) cj[i] = 0.0;
    for (Eigen::Index k = 0; k < inner; ++k) {
      const double* ak = a + k * rows;
      const double bkj = b[k + j * inner];
      for (Eigen::Index i = 0; i < rows; ++i) {
        if constexpr (Mode == Accumulate::Subtract) cj[i] -= ak[i] * bkj;
        else cj[i] += ak[i] * bkj;
      }
    }
  }
}

template <Accumulate Mode>
inline void multiplyIn(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner,
                       Eigen::Index cols) {
  switch (rows) {
    case 1: return multiplyRows<1, Mode>(a, b, c, rows, inner, cols);
    case 2: return multiplyRows<2, Mode>(a, b, c, rows, inner, cols);
    case 3: return multiplyRows<3, Mode>(a, b, c, rows, inner, cols);
    case 4: return multiplyRows<4, Mode>(a, b, c, rows, inner, cols);
    case 5: return multiplyRows<5, Mode>(a, b, c, rows, inner, cols);
    case 6: return multiplyRows<6, Mode>(a, b, c, rows, inner, cols);
    case 7: return multiplyRows<7, Mode>(a, b, c, rows, inner, cols);
    case 8: return multiplyRows<8, Mode>(a, b, c, rows, inner, cols);
    default: return multiplyRows<0, Mode>(a, b, c, rows, inner, cols);
  }
}

}  // namespace detail

/// C (rows × cols) = A B, += A B or −= A B, A rows × inner and B inner × cols, all column-major on
/// raw data. Up to 8 rows the row count is a constant of the inner loops (unrolled); each column of
/// C gets the same operations in the same order whatever the number of columns.
inline void multiply(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner,
                     Eigen::Index cols, Accumulate mode) {
  switch (mode) {
    case Accumulate::Assign: return detail::multiplyIn<Accumulate::Assign>(a, b, c, rows, inner, cols);
    case Accumulate::Add: return detail::multiplyIn<Accumulate::Add>(a, b, c, rows, inner, cols);
    case Accumulate::Subtract: return detail::multiplyIn<Accumulate::Subtract>(a, b, c, rows, inner, cols);
  }
}

/// C (rows × cols) = Aᵀ B, A inner × rows and B inner × cols: a dot product down two columns per
/// coefficient (dotProduct).
inline void multiplyTransposed(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner,
                               Eigen::Index cols) {
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) c[i + j * rows] = dotProduct(a + i * inner, b + j * inner, inner);
}

/// The same on Eigen matrices: C = A B (C resized), C += A B or C −= A B (C of the product's size).
/// C must not share storage with A or B.
inline void multiply(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::MatrixXd& c,
                     Accumulate mode = Accumulate::Assign) {
  assert(a.cols() == b.rows());
  if (mode == Accumulate::Assign) c.resize(a.rows(), b.cols());
  assert(c.rows() == a.rows() && c.cols() == b.cols());
  assert(c.size() == 0 || (c.data() != a.data() && c.data() != b.data()));  // empty matrices' data may all be null
  multiply(a.data(), b.data(), c.data(), a.rows(), a.cols(), b.cols(), mode);
}

/// The same on Eigen vectors: y = A x (y resized), y += A x or y −= A x (y of A's rows).
inline void multiply(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, Eigen::VectorXd& y,
                     Accumulate mode = Accumulate::Assign) {
  assert(a.cols() == x.size());
  if (mode == Accumulate::Assign) y.resize(a.rows());
  assert(y.size() == a.rows());
  multiply(a.data(), x.data(), y.data(), a.rows(), a.cols(), 1, mode);
}

/// y = Aᵀ x (y resized).
inline void multiplyTransposed(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  assert(a.rows() == x.size());
  y.resize(a.cols());
  multiplyTransposed(a.data(), x.data(), y.data(), a.cols(), a.rows(), 1);
}

}  // namespace mbsopt
