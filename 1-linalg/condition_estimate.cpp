#include "mbsopt/linalg/condition_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "mbsopt/linalg/lu_factors.hpp"

namespace mbsopt {

namespace {

constexpr int kMaxIterations = 5;  // LAPACK's ITMAX

double signOf(double v) { return v >= 0.0 ? 1.0 : -1.0; }

/// ‖A‖₁, the largest column sum of |A|.
double oneNorm(const Eigen::MatrixXd& a) {
  const Eigen::Index rows = a.rows();
  double norm = 0.0;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    const double* column = a.data() + j * rows;
    double sum = 0.0;
    for (Eigen::Index i = 0; i < rows; ++i) sum += std::abs(column[i]);
    norm = std::max(norm, sum);
  }
  return norm;
}

}  // namespace

double reciprocalConditionLowerBound(const Eigen::MatrixXd& a, const LuFactors& lu,
                                     Eigen::VectorXd& y) {
  const Eigen::Index n = a.rows();
  if (n == 0) return 1.0;
  const Eigen::MatrixXd& f = lu.matrixLU();
  const double norm = oneNorm(a);
  y.resize(n);
  // U: the comparison matrix's transpose is lower triangular; y = C(U)⁻ᵀ 1 forward, column sums of C(U)⁻¹.
  double inverse_u = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* u = f.data() + i * n;  // column i of U: rows 0..i
    double sum = 1.0;
    for (Eigen::Index k = 0; k < i; ++k) sum += std::abs(u[k]) * y[k];
    y[i] = sum / std::abs(u[i]);
    inverse_u = std::max(inverse_u, y[i]);
  }
  // L (unit diagonal): y = C(L)⁻ᵀ 1 backward.
  double inverse_l = 0.0;
  for (Eigen::Index i = n; i-- > 0;) {
    const double* l = f.data() + i * n;  // column i of L: rows i+1..n−1
    double sum = 1.0;
    for (Eigen::Index k = i + 1; k < n; ++k) sum += std::abs(l[k]) * y[k];
    y[i] = sum;
    inverse_l = std::max(inverse_l, sum);
  }
  const double bound = norm * inverse_u * inverse_l;
  return std::isfinite(bound) && bound > 0.0 ? 1.0 / bound : 0.0;
}

double ConditionEstimator::reciprocalCondition(const Eigen::MatrixXd& a,
                                               const LuFactors& lu) {
  const Eigen::Index n = a.rows();
  if (n == 0) return 1.0;
  const double norm = oneNorm(a);
  // Hager's iteration: a local maximum of ‖A⁻¹x‖₁ over the unit 1-norm ball, searched from
  // x = (1/n, …, 1/n) along the vertices e_j the gradient sign(A⁻¹x)ᵀA⁻¹ points to.
  x_.setConstant(n, 1.0 / static_cast<double>(n));
  sign_.setZero(n);
  double estimate = 0.0;
  Eigen::Index previous_vertex = -1;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    luSolve(lu, x_, y_);
    if (!y_.allFinite()) return 0.0;
    const double candidate = y_.lpNorm<1>();
    if (iteration > 0 && candidate <= estimate) break;  // no ascent: a local maximum
    estimate = candidate;
    // The same signs as at the last vertex: the gradient, and so the next vertex, would repeat.
    if (iteration > 0 && (y_.array() >= 0.0).cwiseEqual(sign_.array() >= 0.0).all()) break;
    sign_ = y_.unaryExpr(&signOf);
    luSolveTransposed(lu, sign_, w_, z_);  // z = A⁻ᵀ sign(y), the gradient of ‖A⁻¹x‖₁ at x
    if (!z_.allFinite()) return 0.0;
    Eigen::Index vertex = 0;
    z_.cwiseAbs().maxCoeff(&vertex);
    if (iteration > 0 && (vertex == previous_vertex || z_.cwiseAbs()[vertex] <= z_.dot(x_))) break;
    previous_vertex = vertex;
    x_.setUnit(n, vertex);
  }
  // Higham's safeguard against the matrices that fool the iteration: x_i = ±(1 + i/(n − 1)),
  // alternating signs, scaled so that 2‖A⁻¹x‖₁/(3n) is a lower bound of ‖A⁻¹‖₁ too.
  for (Eigen::Index i = 0; i < n; ++i)
    x_[i] = (i % 2 == 0 ? 1.0 : -1.0) * (1.0 + (n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0));
  luSolve(lu, x_, y_);
  if (!y_.allFinite()) return 0.0;
  estimate = std::max(estimate, 2.0 * y_.lpNorm<1>() / (3.0 * static_cast<double>(n)));
  return estimate > 0.0 ? 1.0 / (norm * estimate) : 0.0;
}

}  // namespace mbsopt
