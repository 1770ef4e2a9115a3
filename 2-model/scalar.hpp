// Scalar types the recursions are instantiated for (docs/design.md §2: templated on the scalar).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

namespace mbsopt {

template <class Scalar> using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
template <class Scalar> using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
template <class Scalar> using VectorX = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

/// Forward-mode automatic differentiation with a fixed-size derivative vector on the stack:
/// kMaxAdDirections seeded directions per pass, no heap allocation per operation. Fixed size (not
/// "dynamic up to a maximum") so that constants and seeded values always combine coherently.
/// Eight (one AVX-512 register, two AVX2 ones) rather than 16: a pass then wastes fewer unseeded
/// lanes, and a caller can give a pass only the work its directions need (the tram's step
/// derivatives: 10 directions in a full pass of 8 and a pass of 2 velocities that skips the
/// projections' terms); `bench_gradients --benchmark_filter=StepDerivatives` measures the choice.
inline constexpr int kMaxAdDirections = 8;
using AdDerivatives = Eigen::Matrix<double, kMaxAdDirections, 1>;
using AdScalar = Eigen::AutoDiffScalar<AdDerivatives>;

inline double valueOf(double x) { return x; }
inline double valueOf(const AdScalar& x) { return x.value(); }

/// atan2(y, x) of the recursions' scalars. Eigen 3.4's atan2 of two AD scalars returns its
/// derivatives in a vector of dynamic size, allocated on the heap at every call; this one keeps the
/// kMaxAdDirections lanes on the stack, with Eigen's formula d atan2(y, x) = (x dy − y dx)/(x² + y²).
inline double atan2Of(double y, double x) { return std::atan2(y, x); }
inline AdScalar atan2Of(const AdScalar& y, const AdScalar& x) {
  const double squared_hypot = y.value() * y.value() + x.value() * x.value();
  return AdScalar(std::atan2(y.value(), x.value()),
                  (y.derivatives() * x.value() - y.value() * x.derivatives()) / squared_hypot);
}

/// x = 0 in place (for an AD scalar its value and every derivative lane, without a temporary).
inline void setZero(double& x) { x = 0.0; }
inline void setZero(AdScalar& x) {
  x.value() = 0.0;
  x.derivatives().setZero();
}

/// R_e R(axis, θ): the frame R_e turned by the angle θ, given by c = cos θ and s = sin θ, about the
/// unit vector `axis` given in its own axes. About a coordinate axis e_k only the other two columns
/// turn, c_i' = cos·c_i + sin·c_j and c_j' = −sin·c_i + cos·c_j for (i, j, k) cyclic: 12 products
/// instead of Rodrigues' matrix and a 3 × 3 product. The constant matrices stay in double: with AD
/// scalars each product then costs a scaling of the derivatives, not a product rule.
template <class Scalar>
Matrix3<Scalar> turnedAbout(const Matrix3<Scalar>& Re, const Eigen::Vector3d& axis, const Scalar& c, const Scalar& s) {
  for (int k = 0; k < 3; ++k) {
    if (axis[k] != 1.0 || axis[(k + 1) % 3] != 0.0 || axis[(k + 2) % 3] != 0.0) continue;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    Matrix3<Scalar> out;
    out.col(i) = Re.col(i) * c + Re.col(j) * s;
    out.col(j) = Re.col(j) * c - Re.col(i) * s;
    out.col(k) = Re.col(k);
    return out;
  }
  const Scalar one_minus_c = Scalar(1) - c;
  Eigen::Matrix3d skew;  // Rodrigues: R = c 1 + (1 − c) a aᵀ + s [a]×
  skew << 0.0, -axis.z(), axis.y(), axis.z(), 0.0, -axis.x(), -axis.y(), axis.x(), 0.0;
  const Eigen::Matrix3d outer = axis * axis.transpose();
  return Re * Matrix3<Scalar>(c * Eigen::Matrix3d::Identity() + one_minus_c * outer + s * skew);
}

/// The same for the angle itself.
template <class Scalar>
Matrix3<Scalar> turnedAbout(const Matrix3<Scalar>& Re, const Eigen::Vector3d& axis, const Scalar& angle) {
  using std::cos;
  using std::sin;
  return turnedAbout(Re, axis, Scalar(cos(angle)), Scalar(sin(angle)));
}

/// Two unit vectors e, f that complete the unit vector `axis` to a right-handed orthonormal basis
/// (e, f, axis); a deterministic choice.
inline std::array<Eigen::Vector3d, 2> perpendicularPair(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d helper = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e = axis.cross(helper).normalized();
  return {e, axis.cross(e)};
}

/// Copies `values` into AD scalars for one forward-AD pass: input j (global index offset + j) gets
/// the unit derivative direction j − first when it falls in [first, first + count), zero otherwise.
/// Several vectors share one global numbering through their offsets. Into `x`, reusing its storage.
inline void seedVector(const Eigen::Ref<const Eigen::VectorXd>& values, Eigen::Index offset, Eigen::Index first, Eigen::Index count,
                       VectorX<AdScalar>& x) {
  x.resize(values.size());
  for (Eigen::Index j = 0; j < values.size(); ++j) {
    x[j].value() = values[j];
    x[j].derivatives().setZero();
    const Eigen::Index global = offset + j;
    if (global >= first && global < first + count) x[j].derivatives()[global - first] = 1.0;
  }
}

}  // namespace mbsopt
