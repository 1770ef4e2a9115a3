// The dot product of the step's hand-written dense kernels (LU substitutions, Householder
// reflections, Jacobi rotations, the SVD partition's products), on raw contiguous data.
#pragma once

#include <Eigen/Core>

namespace mbsopt {

/// Σ aₖbₖ over n contiguous entries. A plain loop for a few entries; from 16 on Eigen's dot, whose
/// SIMD partial sums the compiler may not form itself (it must keep a loop's order of additions).
inline double dotProduct(const double* a, const double* b, Eigen::Index n) {
  if (n >= 16) return Eigen::Map<const Eigen::VectorXd>(a, n).dot(Eigen::Map<const Eigen::VectorXd>(b, n));
  double sum = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) sum += a[k] * b[k];
  return sum;
}

}  // namespace mbsopt
