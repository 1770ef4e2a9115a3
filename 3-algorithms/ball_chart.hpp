// The rotation-vector chart of a ball joint (BallJointComponent). Its coordinates φ turn the exit
// frame from the entry frame by Rodrigues' formula, with K = [φ]× and θ = |φ|,
//   R(φ) = exp(K) = 1 + s K + α K²,           s = sin θ / θ,  α = (1 − cos θ) / θ²,
// and its angular velocity relative to the entry frame, in the entry frame's axes, is ω = J(φ) φ̇
// with the left Jacobian of SO(3)
//   J(φ) = 1 + α K + β K²,                     β = (θ − sin θ) / θ³,
// whose columns are the joint's three motion axes. J is singular where θ = 2π k (k ≥ 1) and
// nowhere else; the chart is refused beyond θ = kBallChartLimit. The angular acceleration is
// J φ̈ + J̇ φ̇, and with θ̇ = φ·φ̇ / θ
//   J̇ φ̇ = (φ·φ̇) [(α'/θ) φ × φ̇ + (β'/θ) φ × (φ × φ̇)] + β φ̇ × (φ × φ̇).
// Below θ = 1 every coefficient is its power series in θ², which AD differentiates at φ = 0 too.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "mbsopt/model/scalar.hpp"

namespace mbsopt {

/// The largest |φ| [rad] a ball joint's chart is used at: 1.8π, where the smallest singular value of
/// J, sin(θ/2)/(θ/2), is 0.11 (it is 1 at φ = 0 and 0 at θ = 2π).
inline constexpr double kBallChartLimit = 1.8 * std::numbers::pi;

/// 1/n! for n = 0 … 23, the power series' coefficients of ballChartCoefficients.
inline constexpr std::array<double, 24> kInverseFactorials = [] {
  std::array<double, 24> table{};
  double factorial = 1.0;
  for (std::size_t n = 0; n < table.size(); ++n) {
    if (n > 1) factorial *= static_cast<double>(n);
    table[n] = 1.0 / factorial;
  }
  return table;
}();

/// The chart's coefficients at θ² = φ·φ.
template <class Scalar>
struct BallChartCoefficients {
  Scalar sinc, alpha, beta;   ///< s, α, β
  Scalar alpha_rate, beta_rate;  ///< α'(θ)/θ, β'(θ)/θ
};

template <class Scalar>
BallChartCoefficients<Scalar> ballChartCoefficients(const Scalar& theta2) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (valueOf(theta2) < 1.0) {
    // s = Σ (−x)^k/(2k+1)!, α = Σ (−x)^k/(2k+2)!, β = Σ (−x)^k/(2k+3)!, α'/θ = −Σ 2(k+1)(−x)^k/(2k+4)!,
    // β'/θ = −Σ 2(k+1)(−x)^k/(2k+5)! with x = θ²: ten terms leave less than 1e-17 at x < 1.
    constexpr std::size_t kTerms = 10;
    Scalar sinc(0), alpha(0), beta(0), alpha_rate(0), beta_rate(0);
    for (std::size_t k = kTerms; k-- > 0;) {  // Horner, from the smallest term
      const double weight = 2.0 * static_cast<double>(k + 1);
      const double* f = kInverseFactorials.data() + 2 * k;  // f[i] = 1/(2k + i)!
      sinc = Scalar(f[1]) - theta2 * sinc;
      alpha = Scalar(f[2]) - theta2 * alpha;
      beta = Scalar(f[3]) - theta2 * beta;
      alpha_rate = Scalar(-weight * f[4]) - theta2 * alpha_rate;
      beta_rate = Scalar(-weight * f[5]) - theta2 * beta_rate;
    }
    return {sinc, alpha, beta, alpha_rate, beta_rate};
  }
  const Scalar theta = sqrt(theta2);
  const Scalar c = cos(theta), s = sin(theta);
  const Scalar theta4 = theta2 * theta2;
  return {Scalar(s / theta), Scalar((1.0 - c) / theta2), Scalar((theta - s) / (theta2 * theta)),
          Scalar((theta * s - 2.0 * (1.0 - c)) / theta4), Scalar((3.0 * s - theta * c - 2.0 * theta) / (theta4 * theta))};
}

/// [v]× and [v]×² = v vᵀ − |v|² 1, the matrices of v × · and v × (v × ·).
template <class Scalar>
Matrix3<Scalar> crossMatrixOf(const Vector3<Scalar>& v) {
  Matrix3<Scalar> k;
  k << Scalar(0), Scalar(-v.z()), v.y(), v.z(), Scalar(0), Scalar(-v.x()), Scalar(-v.y()), v.x(), Scalar(0);
  return k;
}
template <class Scalar>
Matrix3<Scalar> crossSquaredOf(const Vector3<Scalar>& v, const Scalar& squared_norm) {
  Matrix3<Scalar> k2 = v * v.transpose();
  k2.diagonal().array() -= squared_norm;
  return k2;
}

/// J̇ φ̇ in any axes: φ and φ̇ given in the same axes (the chart's coefficients are invariant).
template <class Scalar>
Vector3<Scalar> ballRateBias(const Vector3<Scalar>& phi, const Vector3<Scalar>& phi_rate, const Scalar& beta,
                             const Scalar& alpha_rate, const Scalar& beta_rate) {
  const Vector3<Scalar> turn = phi.cross(phi_rate);
  return phi.dot(phi_rate) * (alpha_rate * turn + beta_rate * phi.cross(turn)) + beta * phi_rate.cross(turn);
}

}  // namespace mbsopt
