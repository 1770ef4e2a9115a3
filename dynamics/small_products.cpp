#include "dynamics/small_products.hpp"

#include <cassert>

#include "dynamics/dot_product.hpp"

namespace mbsopt {

namespace {

/// multiply() with the row count a constant when Rows > 0 (its inner loops unrolled), the runtime
/// `rows` when Rows = 0: the same operations in the same order either way.
template <int Rows, Accumulate Mode>
void multiplyRows(const double* __restrict a, const double* __restrict b, double* __restrict c,
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
void multiplyIn(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner,
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

}  // namespace

void multiply(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner, Eigen::Index cols,
              Accumulate mode) {
  switch (mode) {
    case Accumulate::Assign: return multiplyIn<Accumulate::Assign>(a, b, c, rows, inner, cols);
    case Accumulate::Add: return multiplyIn<Accumulate::Add>(a, b, c, rows, inner, cols);
    case Accumulate::Subtract: return multiplyIn<Accumulate::Subtract>(a, b, c, rows, inner, cols);
  }
}

void multiplyTransposed(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner,
                        Eigen::Index cols) {
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) c[i + j * rows] = dotProduct(a + i * inner, b + j * inner, inner);
}

void multiply(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::MatrixXd& c, Accumulate mode) {
  assert(a.cols() == b.rows());
  if (mode == Accumulate::Assign) c.resize(a.rows(), b.cols());
  assert(c.rows() == a.rows() && c.cols() == b.cols());
  assert(c.data() != a.data() && c.data() != b.data());
  multiply(a.data(), b.data(), c.data(), a.rows(), a.cols(), b.cols(), mode);
}

}  // namespace mbsopt
