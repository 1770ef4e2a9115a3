#include "mbsopt/linalg/lu_factors.hpp"

#include <cmath>
#include <utility>

namespace mbsopt {

void LuFactors::compute(const Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows();
  lu_ = a;
  rows_.resize(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) rows_[static_cast<std::size_t>(i)] = static_cast<int>(i);
  double* f = lu_.data();
  for (Eigen::Index k = 0; k < n; ++k) {
    double* column_k = f + k * n;
    Eigen::Index pivot = k;
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (std::abs(column_k[i]) > std::abs(column_k[pivot])) pivot = i;
    if (pivot != k) {  // swap rows k and pivot across the whole matrix (L's columns and A's rest)
      for (Eigen::Index j = 0; j < n; ++j) std::swap(f[k + j * n], f[pivot + j * n]);
      std::swap(rows_[static_cast<std::size_t>(k)], rows_[static_cast<std::size_t>(pivot)]);
    }
    if (column_k[k] == 0.0) continue;  // a zero column below the diagonal: nothing to eliminate
    const double inverse_pivot = 1.0 / column_k[k];
    for (Eigen::Index i = k + 1; i < n; ++i) column_k[i] *= inverse_pivot;  // L's column k
    for (Eigen::Index j = k + 1; j < n; ++j) {  // the trailing matrix: A₂₂ −= l_k u_kᵀ
      double* __restrict column_j = f + j * n;
      const double u = column_j[k];
      const double* __restrict l = column_k;
      for (Eigen::Index i = k + 1; i < n; ++i) column_j[i] -= l[i] * u;
    }
  }
}

void LuFactors::assign(const double* lu, const double* rows, Eigen::Index n) {
  lu_ = Eigen::Map<const Eigen::MatrixXd>(lu, n, n);
  rows_.resize(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) rows_[static_cast<std::size_t>(i)] = static_cast<int>(rows[i]);
}

}  // namespace mbsopt
