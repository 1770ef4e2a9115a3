// Closed-form references shared by the tests, computed independently of the code under test.
#pragma once

#include <cmath>
#include <numbers>

namespace mbsopt::test {

/// Complete elliptic integral of the first kind K(k) = π / (2 AGM(1, √(1 − k²))).
inline double ellipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 30 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double mean = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = mean;
  }
  return std::numbers::pi / (2.0 * a);
}

}  // namespace mbsopt::test
