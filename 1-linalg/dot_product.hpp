// The dot product of the step's hand-written dense kernels (LU substitutions, Householder
// reflections, Jacobi rotations, the SVD partition's products), on raw contiguous data.
#pragma once

#include <Eigen/Core>

namespace mbsopt {

namespace detail {

/// Σ aₖbₖ in the order of the loop, over N entries when N > 0 (unrolled), over n when N = 0.
template <int N>
inline double loopDotProduct(const double* a, const double* b, Eigen::Index n) {
  const Eigen::Index length = N > 0 ? N : n;
  double sum = 0.0;
  for (Eigen::Index k = 0; k < length; ++k) sum += a[k] * b[k];
  return sum;
}

}  // namespace detail

/// Σ aₖbₖ over n contiguous entries. Up to 8 entries (the tram's 5 coordinates and 3 closure rows)
/// an unrolled sum in the loop's order, where a loop of a few iterations costs more in its control
/// than in its products (callgrind on BM_TramwaySimulation); up to 15 the plain loop; from 16 on
/// Eigen's dot, whose SIMD partial sums the compiler may not form itself (it must keep a loop's
/// order of additions). Where the target has fused multiply-adds (-march=native) the compiler may
/// fuse the unrolled sum and the loop differently: they can differ in the last bit.
inline double dotProduct(const double* a, const double* b, Eigen::Index n) {
  switch (n) {
    case 0: return 0.0;
    case 1: return detail::loopDotProduct<1>(a, b, n);
    case 2: return detail::loopDotProduct<2>(a, b, n);
    case 3: return detail::loopDotProduct<3>(a, b, n);
    case 4: return detail::loopDotProduct<4>(a, b, n);
    case 5: return detail::loopDotProduct<5>(a, b, n);
    case 6: return detail::loopDotProduct<6>(a, b, n);
    case 7: return detail::loopDotProduct<7>(a, b, n);
    case 8: return detail::loopDotProduct<8>(a, b, n);
    default: break;
  }
  if (n >= 16) return Eigen::Map<const Eigen::VectorXd>(a, n).dot(Eigen::Map<const Eigen::VectorXd>(b, n));
  return detail::loopDotProduct<0>(a, b, n);
}

}  // namespace mbsopt
