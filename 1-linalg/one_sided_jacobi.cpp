#include "mbsopt/linalg/one_sided_jacobi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mbsopt/linalg/dot_product.hpp"

namespace mbsopt {

namespace {

/// (x, y) ← (c x − s y, s x + c y) over n entries.
void rotate(double* __restrict x, double* __restrict y, Eigen::Index n, double c, double s) {
  for (Eigen::Index i = 0; i < n; ++i) {
    const double xi = x[i], yi = y[i];
    x[i] = c * xi - s * yi;
    y[i] = s * xi + c * yi;
  }
}

}  // namespace

void OneSidedJacobiSvd::startFromIdentity(const Eigen::MatrixXd& a) {
  warm_starts_ = 0;
  work_columns_ = a;
  work_rotations_.setIdentity(a.cols(), a.cols());
}

void OneSidedJacobiSvd::compute(const Eigen::MatrixXd& a) {
  startFromIdentity(a);
  rotateToOrthogonal(0.0);
}

void OneSidedJacobiSvd::update(const Eigen::MatrixXd& a, double orthogonality) {
  if (rotations_.rows() != a.cols() || columns_.rows() != a.rows() || ++warm_starts_ >= kWarmStartsBeforeCold) {
    startFromIdentity(a);
  } else {
    work_rotations_ = rotations_;
    work_columns_.noalias() = a.lazyProduct(rotations_);  // a few columns: no blocked product
  }
  rotateToOrthogonal(orthogonality);
}

void OneSidedJacobiSvd::rotateToOrthogonal(double orthogonality) {
  const Eigen::Index rows = work_columns_.rows(), cols = work_columns_.cols();
  constexpr double epsilon = std::numeric_limits<double>::epsilon();
  squared_norms_.resize(cols);
  double frobenius_squared = 0.0;
  for (Eigen::Index j = 0; j < cols; ++j) {
    const double* column = work_columns_.data() + j * rows;
    squared_norms_[j] = dotProduct(column, column, rows);
    frobenius_squared += squared_norms_[j];
  }
  const double negligible_squared = epsilon * epsilon * frobenius_squared;
  const double tolerance_squared = orthogonality > 0.0 ? orthogonality * orthogonality
                                                       : static_cast<double>(rows) * epsilon * epsilon;  // (√rows · ε)²
  sweeps_ = 0;
  bool rotated = cols > 1;
  while (rotated && sweeps_ < kMaxSweeps) {
    rotated = false;
    ++sweeps_;
    double largest = 0.0;  // the largest γ²/(αβ) this sweep rotated away
    for (Eigen::Index p = 0; p + 1 < cols; ++p)
      for (Eigen::Index q = p + 1; q < cols; ++q) {
        const double alpha = squared_norms_[p], beta = squared_norms_[q];
        if (alpha <= negligible_squared || beta <= negligible_squared) continue;
        double* column_p = work_columns_.data() + p * rows;
        double* column_q = work_columns_.data() + q * rows;
        const double gamma = dotProduct(column_p, column_q, rows);
        if (gamma * gamma <= tolerance_squared * alpha * beta) continue;  // |γ| ≤ tol √α √β, without two roots
        largest = std::max(largest, gamma * gamma / (alpha * beta));
        // The rotation that diagonalises [α γ; γ β] (Golub and Van Loan, sym.schur2): the smaller
        // root t = tan θ of t² + 2ζt − 1 = 0, ζ = (β − α)/(2γ). ζ² cannot overflow: past the tests
        // above, |ζ| < √(max(α, β)/min(α, β))/(2·tolerance) ≤ 1/(2ε·tolerance) ≈ 1e31 (hypot's care
        // cost 13 % of a step).
        const double zeta = (beta - alpha) / (2.0 * gamma);
        const double t = (zeta >= 0.0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1.0 + zeta * zeta));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = c * t;
        rotate(column_p, column_q, rows, c, s);
        rotate(work_rotations_.data() + p * cols, work_rotations_.data() + q * cols, cols, c, s);
        // The rotation's diagonal, α − tγ and β + tγ (sym.schur2), instead of two more dot products (as
        // LAPACK's xGESVJ); a norm that falls below a quarter of its old value is summed afresh, where
        // the update's round-off, ε (α + |tγ|), would no longer be small relative to it.
        const double shift = t * gamma;
        squared_norms_[p] = alpha - shift >= 0.25 * alpha ? alpha - shift : dotProduct(column_p, column_p, rows);
        squared_norms_[q] = beta + shift >= 0.25 * beta ? beta + shift : dotProduct(column_q, column_q, rows);
        rotated = true;
      }
    if (rotated && orthogonality > 0.0 && confirmedByConvergence(largest, orthogonality, negligible_squared)) break;
  }
  // Σ from the columns themselves: the updates' round-off would otherwise stay in the singular values.
  for (Eigen::Index j = 0; j < cols; ++j) {
    const double* column = work_columns_.data() + j * rows;
    squared_norms_[j] = dotProduct(column, column, rows);
  }
  // Columns in decreasing norm, equal norms in their order (std::sort: stable_sort would allocate).
  order_.resize(static_cast<std::size_t>(cols));
  for (Eigen::Index j = 0; j < cols; ++j) order_[static_cast<std::size_t>(j)] = j;
  std::sort(order_.begin(), order_.end(), [&](Eigen::Index i, Eigen::Index j) {
    return squared_norms_[i] > squared_norms_[j] || (squared_norms_[i] == squared_norms_[j] && i < j);
  });
  columns_.resize(rows, cols);
  rotations_.resize(cols, cols);
  sigma_.resize(cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    const Eigen::Index from = order_[static_cast<std::size_t>(j)];
    columns_.col(j) = work_columns_.col(from);
    rotations_.col(j) = work_rotations_.col(from);
    sigma_[j] = std::sqrt(squared_norms_[from]);
  }
}

bool OneSidedJacobiSvd::confirmedByConvergence(double largest, double orthogonality, double negligible_squared) const {
  // Cyclic Jacobi converges quadratically once the columns' products are below the gaps between their
  // squared norms (Wilkinson 1962): a rotation of columns p and r turns them by about μ_pr/g_pr (μ: a
  // product relative to the norms, g: the relative gap |α − β|/√(αβ)) and so puts back μ_pr μ_rq/g_pr
  // into a pair p, q rotated before. A sweep that rotated away at most μ leaves about μ²/g, g the
  // smallest gap, summed over a few pairs; with kConvergenceSafety times that below the orthogonality
  // asked for, the sweep that would only confirm it is not made.
  if (largest > orthogonality) return false;  // μ² ≤ τ: well inside the quadratic regime
  double gap = std::numeric_limits<double>::infinity();
  const Eigen::Index cols = squared_norms_.size();
  for (Eigen::Index p = 0; p + 1 < cols; ++p)
    for (Eigen::Index q = p + 1; q < cols; ++q) {
      const double alpha = squared_norms_[p], beta = squared_norms_[q];
      if (alpha > negligible_squared && beta > negligible_squared)
        gap = std::min(gap, std::abs(alpha - beta) / std::sqrt(alpha * beta));
    }
  return kConvergenceSafety * largest <= gap * orthogonality;
}

void OneSidedJacobiSvd::solveLeastSquares(const Eigen::VectorXd& b, double relative_threshold, Eigen::VectorXd& x,
                                          Eigen::VectorXd& work) const {
  const Eigen::Index rows = columns_.rows(), cols = columns_.cols();
  work.resize(cols);
  const double cutoff = cols > 0 ? relative_threshold * sigma_[0] : 0.0;
  for (Eigen::Index j = 0; j < cols; ++j)  // Σ⁺ Xᵀ b = Σ⁺ Σ⁻¹ (X Σ)ᵀ b
    work[j] = sigma_[j] > cutoff ? dotProduct(columns_.data() + j * rows, b.data(), rows) / (sigma_[j] * sigma_[j]) : 0.0;
  x.noalias() = rotations_ * work;
}

}  // namespace mbsopt
