#include "mbsopt/linalg/householder_basis.hpp"

#include <cmath>

#include "mbsopt/linalg/dot_product.hpp"

namespace mbsopt {

namespace {

/// y ← H y = y − τ v (vᵀ y) on the entries k … n − 1 of a column y, v stored below row k of `v`.
void reflect(const double* __restrict v, double tau, Eigen::Index k, Eigen::Index n, double* __restrict y) {
  const double w = tau * (y[k] + dotProduct(v + k + 1, y + k + 1, n - k - 1));
  y[k] -= w;
  for (Eigen::Index i = k + 1; i < n; ++i) y[i] -= w * v[i];
}

}  // namespace

void HouseholderBasis::compute(const Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows(), r = a.cols();
  reflectors_ = a;
  tau_.resize(r);
  for (Eigen::Index k = 0; k < r; ++k) {
    double* v = reflectors_.data() + k * n;
    double tail = 0.0;
    for (Eigen::Index i = k + 1; i < n; ++i) tail += v[i] * v[i];
    if (tail == 0.0) {  // already e_k times a number: H_k = I (xLARFG)
      tau_[k] = 0.0;
      continue;
    }
    // H x = β e_k with β = −sign(x_k)‖x‖ (no cancellation in x_k − β), v = (x − β e_k)/(x_k − β).
    const double x = v[k];
    const double beta = -std::copysign(std::sqrt(x * x + tail), x);
    tau_[k] = (beta - x) / beta;
    const double scale = 1.0 / (x - beta);
    for (Eigen::Index i = k + 1; i < n; ++i) v[i] *= scale;
    v[k] = beta;
    for (Eigen::Index j = k + 1; j < r; ++j) reflect(v, tau_[k], k, n, reflectors_.data() + j * n);
  }
}

void HouseholderBasis::assign(const double* reflectors, const double* tau, Eigen::Index n, Eigen::Index r) {
  reflectors_ = Eigen::Map<const Eigen::MatrixXd>(reflectors, n, r);
  tau_ = Eigen::Map<const Eigen::VectorXd>(tau, r);
}

void HouseholderBasis::complement(Eigen::MatrixXd& out) const {
  const Eigen::Index n = reflectors_.rows(), r = tau_.size();
  out.setZero(n, n - r);
  for (Eigen::Index j = 0; j < n - r; ++j) out(r + j, j) = 1.0;
  for (Eigen::Index k = r; k-- > 0;)  // Q e_j = H_0 (⋯ (H_{r−1} e_j))
    for (Eigen::Index j = 0; j < n - r; ++j) reflect(reflectors_.data() + k * n, tau_[k], k, n, out.data() + j * n);
}

void HouseholderBasis::transformSimilar(Eigen::MatrixXd& x) {
  const Eigen::Index n = reflectors_.rows(), r = tau_.size();
  for (Eigen::Index k = 0; k < r; ++k)  // Qᵀ x = H_{r−1} (⋯ (H_0 x)), column by column
    for (Eigen::Index j = 0; j < n; ++j) reflect(reflectors_.data() + k * n, tau_[k], k, n, x.data() + j * n);
  row_work_.resize(n);
  double* __restrict w = row_work_.data();
  for (Eigen::Index k = 0; k < r; ++k) {  // (Qᵀ x) Q = ((Qᵀ x) H_0) ⋯ H_{r−1}: x ← x − τ (x v) vᵀ
    const double* v = reflectors_.data() + k * n;
    const double tau = tau_[k];
    double* __restrict column_k = x.data() + k * n;
    for (Eigen::Index i = 0; i < n; ++i) w[i] = column_k[i];
    for (Eigen::Index c = k + 1; c < n; ++c) {
      const double* __restrict column = x.data() + c * n;
      for (Eigen::Index i = 0; i < n; ++i) w[i] += column[i] * v[c];
    }
    for (Eigen::Index i = 0; i < n; ++i) w[i] *= tau;
    for (Eigen::Index i = 0; i < n; ++i) column_k[i] -= w[i];
    for (Eigen::Index c = k + 1; c < n; ++c) {
      double* __restrict column = x.data() + c * n;
      for (Eigen::Index i = 0; i < n; ++i) column[i] -= w[i] * v[c];
    }
  }
}

}  // namespace mbsopt
