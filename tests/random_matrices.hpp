// Random test matrices: entries uniform in [−1, 1] from a seeded generator, so every run of a test
// sees the same matrices.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <random>

namespace mbsopt::test_support {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

inline Eigen::MatrixXd randomMatrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& generator) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  return Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return entry(generator); });
}

}  // namespace mbsopt::test_support
