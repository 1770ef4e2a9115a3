// Planar pendulum on a revolute joint about ground z, integrated by Newmark's trapezoidal rule.
//
// Convention: the body frame is rotated by the joint angle q about z; the centre of mass sits at
// distance L along the body's x axis, so it is at L(cos q, sin q, 0). Gravity is −g along y, so
// q = 0 is horizontal and the pendulum hangs at q = −π/2. With φ = q + π/2 (the swing angle from
// the vertical) the potential is V = m g L sin q = −m g L cos φ and the equation of motion
//     I_O φ̈ = −m g L sin φ,   I_O = I_c,zz + m L²   (parallel-axis theorem),
// with small-angle angular frequency ω = √(m g L / I_O) and period T₀ = 2π/ω.
#include <gtest/gtest.h>

#include "tests/closed_forms.hpp"

#include <cmath>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/integrators/newmark.hpp"

using namespace mbsopt;

namespace {

constexpr double kGravity = 9.81;

struct Pendulum {
  double mass = 1.0;
  double length = 1.0;
  double inertia_zz = 0.01;  // small but positive inertia about the centre of mass

  double pivotInertia() const { return inertia_zz + mass * length * length; }
  double angularFrequency() const { return std::sqrt(mass * kGravity * length / pivotInertia()); }
  double smallAnglePeriod() const { return 2.0 * M_PI / angularFrequency(); }
  /// Energy with the hanging rest state as zero: ½ I_O q̇² + m g L (1 + sin q) = ½ I_O φ̇² + m g L (1 − cos φ).
  double energy(double q, double rate) const {
    return 0.5 * pivotInertia() * rate * rate + mass * kGravity * length * (1.0 + std::sin(q));
  }
};

Model buildModel(const Pendulum& p) {
  Model model;
  const FrameIndex arm = model.addRevolute("pivot", Model::ground, Eigen::Vector3d::UnitZ());
  model.addBody("bob", arm, p.mass, Eigen::Vector3d(p.length, 0.0, 0.0), p.inertia_zz * Eigen::Matrix3d::Identity());
  model.setGravity({0.0, -kGravity, 0.0});
  return model;
}

/// Released at rest from swing angle φ₀ (so φ₀ is the amplitude).
Trajectory releaseFrom(const Model& model, double swing_angle, double step, double end_time) {
  const Eigen::VectorXd q0 = Eigen::VectorXd::Constant(1, swing_angle - M_PI / 2.0);
  const Eigen::VectorXd v0 = Eigen::VectorXd::Zero(1);
  return NewmarkIntegrator(model, NewmarkSettings{.step = step, .end_time = end_time}).simulate(q0, v0);
}

/// Times at which φ = q + π/2 crosses zero upwards, by linear interpolation between samples. At a
/// zero of φ, φ̈ = −ω² sin φ = 0, so the chord's error in the crossing time is O(ω²h³), ~1e-8 s here.
std::vector<double> upwardZeroCrossings(const Trajectory& traj) {
  std::vector<double> crossings;
  for (Eigen::Index n = 1; n < traj.time.size(); ++n) {
    const double before = traj.q(0, n - 1) + M_PI / 2.0, after = traj.q(0, n) + M_PI / 2.0;
    if (before < 0.0 && after >= 0.0)
      crossings.push_back(traj.time[n - 1] + (traj.time[n] - traj.time[n - 1]) * before / (before - after));
  }
  return crossings;
}

using mbsopt::test::ellipticK;

TEST(Pendulum, SmallAnglePeriodIncludesAmplitudeAndNewmarkCorrections) {
  const Pendulum p;
  const Model model = buildModel(p);
  const double amplitude = 0.05;  // rad
  const double h = 1e-2;
  const double T0 = p.smallAnglePeriod();  // ≈ 2.016 s
  const int periods = 20;
  const Trajectory traj = releaseFrom(model, amplitude, h, (periods + 1) * T0);
  const std::vector<double> crossings = upwardZeroCrossings(traj);
  ASSERT_GE(crossings.size(), static_cast<std::size_t>(periods));
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);

  // Expected period: T₀ times
  //  - the exact amplitude factor (2/π) K(sin(φ₀/2)) = 1 + φ₀²/16 + 11φ₀⁴/3072 + …  (1.56e-4 here)
  //  - the trapezoidal rule's period elongation: the discrete frequency of a linear oscillator is
  //    ω_h = (2/h) atan(ωh/2), so T_h/T = 1 + (ωh)²/12 + O((ωh)⁴)                  (8.0e-5 here)
  // Neglected: (ωh)⁴ terms (~5e-9), the product of the two corrections (~1e-8), the crossing
  // interpolation (~1e-8 s per crossing, divided by 20 periods) and the Newton tolerance
  // (1e-10 relative). A relative tolerance of 1e-6 is well above those and 1/200 of the
  // corrections being checked, so it verifies both of them.
  const double w = p.angularFrequency();
  const double amplitude_factor = 2.0 / M_PI * ellipticK(std::sin(amplitude / 2.0));
  EXPECT_NEAR(amplitude_factor - 1.0, amplitude * amplitude / 16.0, 1e-7);  // the φ₀²/16 law
  const double newmark_factor = 1.0 + w * w * h * h / 12.0;
  const double expected = T0 * amplitude_factor * newmark_factor;
  EXPECT_NEAR(measured / expected - 1.0, 0.0, 1e-6) << "measured " << measured << " s, small-angle " << T0
                                                  << " s, expected " << expected << " s";
}

TEST(Pendulum, EnergyErrorStaysBoundedOverTwoHundredPeriods) {
  const Pendulum p;
  const Model model = buildModel(p);
  const double amplitude = 1.0;  // rad, ≈ 57°: clearly nonlinear
  const double h = 2e-2;
  const double period = p.smallAnglePeriod() * 2.0 / M_PI * ellipticK(std::sin(amplitude / 2.0));
  const Trajectory traj = releaseFrom(model, amplitude, h, 200.0 * period);

  const double e0 = p.energy(traj.q(0, 0), traj.v(0, 0));
  const Eigen::Index count = traj.time.size();
  auto maxRelativeError = [&](Eigen::Index first, Eigen::Index last) {
    double worst = 0.0;
    for (Eigen::Index n = first; n < last; ++n)
      worst = std::max(worst, std::abs(p.energy(traj.q(0, n), traj.v(0, n)) - e0) / e0);
    return worst;
  };
  const double first_quarter = maxRelativeError(0, count / 4);
  const double last_quarter = maxRelativeError(count - count / 4, count);

  // Bound. The trapezoidal rule gives ½I_O(vₙ₊₁² − vₙ²) = ½I_O(aₙ + aₙ₊₁)Δq = −½(V'(qₙ) + V'(qₙ₊₁))Δq,
  // the trapezoidal quadrature of −∫V'dq, so each step changes the energy by exactly the
  // quadrature error: Eₙ₊₁ − Eₙ = −V'''(ξ)Δq³/12 with Δq ≈ q̇h. Summed, Eₙ − E₀ ≈ −(h²/12)∫V'''(q) q̇² dq
  // along the path. V''' = −mgL sin φ is odd and q̇² even in φ, so the integral cancels over each
  // swing (no drift) and is largest at the bottom, where it equals
  //     (h²/12) ∫₀^φ₀ mgL sin φ · 2mgL(cos φ − cos φ₀)/I_O dφ = (h²/12)(mgL)²(1 − cos φ₀)²/I_O,
  // i.e. relative to E₀ = mgL(1 − cos φ₀):  max |E − E₀|/E₀ ≈ (ωh)²(1 − cos φ₀)/12  (1.5e-4 here).
  // The O(h⁴) remainder of that estimate is ~(ωh)² ≈ 0.4 % of it; 1.1 × bounds it.
  const double w = p.angularFrequency();
  const double bound = w * w * h * h * (1.0 - std::cos(amplitude)) / 12.0;
  EXPECT_LE(first_quarter, 1.1 * bound);
  EXPECT_LE(last_quarter, 1.1 * bound);
  EXPECT_GE(first_quarter, 0.9 * bound) << "the energy error should be the predicted O(h²) oscillation";
  // No secular drift: the error late in the run is no larger than early on.
  EXPECT_LE(last_quarter, 1.5 * first_quarter);
}

}  // namespace
