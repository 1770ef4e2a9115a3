// Keeping and copying an SvdPartition's factors (svd_partition.hpp): into the step matrices a
// simulation keeps for the exact gradients (NewmarkIntegrator::keepStepMatrices), and from the
// partition a time point computed to the solver of a sweep (AugmentedSolver). In a file of its own,
// so that these copies do not change what the compiler inlines into the solves.
#include <algorithm>

#include "mbsopt/algorithms/svd_partition.hpp"

namespace mbsopt {

void SvdPartition::copyConstraintFactors(const SvdPartition& other) {
  threshold_ = other.threshold_;
  rank_ = other.rank_;
  singular_values_ = other.singular_values_;
  u1_ = other.u1_;
  v1_ = other.v1_;
  inverse_s1_ = other.inverse_s1_;
  complement_ = other.complement_;
  v2_stale_ = other.v2_stale_;
  if (!v2_stale_) v2_ = other.v2_;
  x_r_.resize(rank_);
  inverse_ = nullptr;
}

// The stored layout, c = min(m, n) places for the rank r: r, the c singular values, U₁ (m × c),
// V₁ (n × c), S₁⁻¹ (c), V₁'s reflectors (n × c) and their τ (c); the columns from r on unused.
Eigen::Index SvdPartition::storedSize(Eigen::Index m, Eigen::Index n) {
  const Eigen::Index c = std::min(m, n);
  return 1 + c + m * c + n * c + c + n * c + c;
}

void SvdPartition::store(double* out) const {
  const Eigen::Index m = u1_.rows(), n = v1_.rows(), c = std::min(m, n);
  std::fill(out, out + storedSize(m, n), 0.0);
  *out = static_cast<double>(rank_);
  std::copy(singular_values_.data(), singular_values_.data() + singular_values_.size(), out + 1);
  double* u1 = out + 1 + c;
  double* v1 = u1 + m * c;
  double* inverse_s1 = v1 + n * c;
  double* reflectors = inverse_s1 + c;
  double* tau = reflectors + n * c;
  std::copy(u1_.data(), u1_.data() + u1_.size(), u1);
  std::copy(v1_.data(), v1_.data() + v1_.size(), v1);
  std::copy(inverse_s1_.data(), inverse_s1_.data() + inverse_s1_.size(), inverse_s1);
  std::copy(complement_.reflectors().data(), complement_.reflectors().data() + complement_.reflectors().size(),
            reflectors);
  std::copy(complement_.tau().data(), complement_.tau().data() + complement_.tau().size(), tau);
}

void SvdPartition::load(const double* in, Eigen::Index m, Eigen::Index n) {
  if (m == 0) {  // nothing stored but the rank: the partition of B with no rows
    setConstraintJacobian(Eigen::MatrixXd(0, n));
    return;
  }
  const Eigen::Index c = std::min(m, n);
  rank_ = static_cast<int>(in[0]);
  singular_values_ = Eigen::Map<const Eigen::VectorXd>(in + 1, c);
  const double* u1 = in + 1 + c;
  const double* v1 = u1 + m * c;
  const double* inverse_s1 = v1 + n * c;
  const double* reflectors = inverse_s1 + c;
  const double* tau = reflectors + n * c;
  u1_ = Eigen::Map<const Eigen::MatrixXd>(u1, m, rank_);
  v1_ = Eigen::Map<const Eigen::MatrixXd>(v1, n, rank_);
  inverse_s1_ = Eigen::Map<const Eigen::VectorXd>(inverse_s1, rank_);
  complement_.assign(reflectors, tau, n, rank_);
  v2_stale_ = true;
  x_r_.resize(rank_);
  inverse_ = nullptr;
}

// The stored layout: V₂ (n × f, f = n − r, in n² places), the LU factors of V₂ᵀJV₂ (f × f, in n²
// places) and their row order (f, in n places).
void SvdPartition::storeFactorization(double* out) const {
  const Eigen::Index n = v1_.rows(), f = n - rank_;
  std::fill(out, out + storedFactorizationSize(n), 0.0);
  const Eigen::MatrixXd& v2 = freeDirections();
  std::copy(v2.data(), v2.data() + v2.size(), out);
  if (f == 0) return;  // nothing factored (setIterationMatrix returns before the LU)
  std::copy(reduced_.matrixLU().data(), reduced_.matrixLU().data() + f * f, out + n * n);
  for (Eigen::Index i = 0; i < f; ++i) out[2 * n * n + i] = static_cast<double>(reduced_.rows()[static_cast<std::size_t>(i)]);
}

void SvdPartition::loadFactorization(const double* in, const Eigen::MatrixXd& J) {
  const Eigen::Index n = v1_.rows(), f = n - rank_;
  inverse_ = nullptr;
  J_ = J;
  v2_ = Eigen::Map<const Eigen::MatrixXd>(in, n, f);
  v2_stale_ = false;
  if (f > 0) reduced_.assign(in + n * n, in + 2 * n * n, f);
}

Eigen::Index SvdPartition::storedFactoredSize(Eigen::Index m, Eigen::Index n) {
  return storedSize(m, n) + (m > 0 ? storedFactorizationSize(n) : 0);
}

void SvdPartition::storeFactored(double* out) const {
  const Eigen::Index m = u1_.rows(), n = v1_.rows();
  store(out);
  if (m > 0) storeFactorization(out + storedSize(m, n));
}

void SvdPartition::loadFactored(const double* in, Eigen::Index m, Eigen::Index n, const Eigen::MatrixXd& J) {
  load(in, m, n);
  if (m > 0) loadFactorization(in + storedSize(m, n), J);
}

}  // namespace mbsopt
