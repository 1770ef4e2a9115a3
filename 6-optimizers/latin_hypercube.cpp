#include "mbsopt/optimizers/latin_hypercube.hpp"

#include <numeric>
#include <random>
#include <stdexcept>
#include <utility>

namespace mbsopt {

namespace {

/// Uniform in [0, 1) from the 53 high bits of one draw of the standard's exactly specified engine.
double unitUniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

/// Uniform in {0, …, n − 1} by rejection, free of the modulo bias.
std::uint64_t belowN(std::mt19937_64& engine, std::uint64_t n) {
  const std::uint64_t limit = std::mt19937_64::max() - std::mt19937_64::max() % n;
  for (;;)
    if (const std::uint64_t draw = engine(); draw < limit) return draw % n;
}

}  // namespace

std::vector<Eigen::VectorXd> latinHypercube(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int count,
                                            std::uint64_t seed) {
  if (lower.size() != upper.size() || !lower.allFinite() || !upper.allFinite() || (lower.array() > upper.array()).any())
    throw std::invalid_argument("Latin hypercube: the bounds must be finite, with lower ≤ upper");
  if (count < 0) throw std::invalid_argument("Latin hypercube: a negative number of points");
  std::mt19937_64 engine(seed);
  const auto n = static_cast<std::size_t>(count);
  std::vector<Eigen::VectorXd> points(n, Eigen::VectorXd(lower.size()));
  std::vector<std::size_t> stratum(n);
  for (Eigen::Index j = 0; j < lower.size(); ++j) {
    std::iota(stratum.begin(), stratum.end(), std::size_t{0});
    for (std::size_t i = n; i > 1; --i) std::swap(stratum[i - 1], stratum[belowN(engine, i)]);  // Fisher–Yates
    for (std::size_t k = 0; k < n; ++k) {
      const double u = (static_cast<double>(stratum[k]) + unitUniform(engine)) / static_cast<double>(n);
      points[k][j] = lower[j] + u * (upper[j] - lower[j]);
    }
  }
  return points;
}

}  // namespace mbsopt
