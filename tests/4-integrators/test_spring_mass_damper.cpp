// One-degree-of-freedom spring-mass-damper on a prismatic joint, integrated by Newmark's
// trapezoidal rule (β = 1/4, γ = 1/2) and compared with the closed-form solution.
//
// The joint slides along ground y; gravity acts along −y, so the equilibrium is shifted from the
// spring's rest value r to x_eq = r − m g / k. With y = x − x_eq the motion is
//     m ÿ + c ẏ + k y = 0,   y(t) = Re(C e^{s t}),   s = −ζω₀ + i ω_d,
// an underdamped oscillator (ζ < 1).
//
// Error of the trapezoidal rule on this linear system: Newmark with β = 1/4, γ = 1/2 *is* the
// trapezoidal rule on (y, ẏ), whose amplification factor for an eigenvalue s is
//     z = (1 + sh/2) / (1 − sh/2) = exp(s_h h),   s_h = (2/h) artanh(sh/2) = s + s³h²/12 + O(h⁴).
// The eigenvectors are those of the continuous system, so the discrete solution is exactly
// y_n = Re(C e^{s_h t_n}) and its error is Re(C e^{st}(e^{(s_h − s)t} − 1)), bounded by
//     |y_n − y(t_n)| ≤ |C| e^{−ζω₀ t} t |s_h − s| e^{|s_h − s| t},   |s_h − s| ≈ ω₀³h²/12,
// i.e. O(h²) globally, growing linearly with t (a phase error) under the decaying envelope.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "mbsopt/model/model.hpp"
#include "mbsopt/integrators/newmark.hpp"

using namespace mbsopt;

namespace {

constexpr double kGravity = 9.81;

struct Oscillator {
  double mass = 2.0;
  double stiffness = 200.0;  // ω₀ = 10 rad/s, period ≈ 0.63 s
  double damping_ratio = 0.05;
  double rest = 0.1;

  double naturalFrequency() const { return std::sqrt(stiffness / mass); }
  double damping() const { return 2.0 * damping_ratio * std::sqrt(stiffness * mass); }
  double equilibrium() const { return rest - mass * kGravity / stiffness; }
  double period() const { return 2.0 * M_PI / naturalFrequency(); }
  /// Continuous eigenvalue s = −ζω₀ + iω_d.
  std::complex<double> eigenvalue() const {
    const double w0 = naturalFrequency();
    return {-damping_ratio * w0, w0 * std::sqrt(1.0 - damping_ratio * damping_ratio)};
  }
};

struct InitialState {
  double displacement = 0.05;  // y(0) = x(0) − x_eq
  double velocity = 0.3;       // ẏ(0)
};

Model buildModel(const Oscillator& osc) {
  Model model;
  const FrameIndex slider = model.addPrismatic("slider", Model::ground, Eigen::Vector3d::UnitY());
  model.addBody("mass", slider, osc.mass, Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity());
  model.addJointSpringDamper("spring", "slider", osc.stiffness, osc.damping(), osc.rest);
  model.setGravity({0.0, -kGravity, 0.0});
  return model;
}

/// Complex amplitude C with y(t) = Re(C e^{st}) matching y(0) and ẏ(0) (conjugate-pair modes).
std::complex<double> modalAmplitude(const Oscillator& osc, const InitialState& init) {
  const std::complex<double> s = osc.eigenvalue();
  // y = Re(C e^{st}): y(0) = Re C, ẏ(0) = Re(C s)  →  C = y0 − i (v0 − y0 Re s) / Im s.
  return {init.displacement, -(init.velocity - init.displacement * s.real()) / s.imag()};
}

double exactDisplacement(const Oscillator& osc, const InitialState& init, double t) {
  return (modalAmplitude(osc, init) * std::exp(osc.eigenvalue() * t)).real();
}

Trajectory simulate(const Model& model, const Oscillator& osc, const InitialState& init, double step,
                    double end_time) {
  Eigen::VectorXd q0(1), v0(1);
  q0 << osc.equilibrium() + init.displacement;
  v0 << init.velocity;
  return NewmarkIntegrator(model, NewmarkSettings{.step = step, .end_time = end_time}).simulate(q0, v0);
}

/// max over every `stride`-th stored point of |x_n − x(t_n)|.
double maxDisplacementError(const Trajectory& traj, const Oscillator& osc, const InitialState& init,
                            int stride = 1) {
  double worst = 0.0;
  for (Eigen::Index n = 0; n < traj.time.size(); n += stride) {
    const double y = traj.q(0, n) - osc.equilibrium();
    worst = std::max(worst, std::abs(y - exactDisplacement(osc, init, traj.time[n])));
  }
  return worst;
}

/// Mechanical energy: kinetic + spring + gravity potential (gravity along −y, joint along +y).
double mechanicalEnergy(const Oscillator& osc, double x, double v) {
  return 0.5 * osc.mass * v * v + 0.5 * osc.stiffness * (x - osc.rest) * (x - osc.rest) +
         osc.mass * kGravity * x;
}

TEST(SpringMassDamper, MatchesClosedFormWithinTrapezoidalErrorBound) {
  const Oscillator osc;
  const InitialState init;
  const Model model = buildModel(osc);
  const double h = 1e-3;
  const double end_time = 5.0 * osc.period();
  const Trajectory traj = simulate(model, osc, init, h, end_time);

  // Bound from the header: |e(t)| ≤ |C| e^{−ζω₀t} t δ e^{δt}, δ = |s_h − s| with the exact
  // s_h = (2/h) artanh(sh/2). The only other errors are the Newton tolerance (1e-10 relative on
  // q̈, and the system is linear so Newton is exact after one iteration) and round-off, far
  // below the O(h²) term (≈ 4e-6 here); a 5 % margin covers them.
  const std::complex<double> s = osc.eigenvalue();
  const double delta = std::abs(2.0 / h * std::atanh(s * h / 2.0) - s);
  ASSERT_NEAR(delta, std::pow(osc.naturalFrequency(), 3) * h * h / 12.0, 1e-3 * delta);  // the O(h²) rate
  const double amplitude = std::abs(modalAmplitude(osc, init));
  double largest_error = 0.0, largest_envelope = 0.0;
  for (Eigen::Index n = 0; n < traj.time.size(); ++n) {
    const double t = traj.time[n];
    const double envelope = amplitude * std::exp(s.real() * t) * t * delta * std::exp(delta * t);
    const double error = std::abs(traj.q(0, n) - osc.equilibrium() - exactDisplacement(osc, init, t));
    ASSERT_LE(error, 1.05 * envelope + 1e-12) << "at t = " << t;
    largest_error = std::max(largest_error, error);
    largest_envelope = std::max(largest_envelope, envelope);
  }
  // The error must also be of the predicted size, not merely below it: |Re(C e^{st} δt)| touches
  // its envelope twice per period, so over several periods its max nears the envelope's max.
  EXPECT_GT(largest_error, 0.8 * largest_envelope);
}

TEST(SpringMassDamper, GlobalErrorIsSecondOrder) {
  const Oscillator osc;
  const InitialState init;
  const Model model = buildModel(osc);
  const double end_time = 5.0 * osc.period();
  // ω₀h = 0.1 at the coarsest step: well inside the asymptotic range, where the error is
  // e ∝ δ ∝ h² (1 + O(ω₀²h²)); halving h divides it by 4 up to ~1 %. Errors are compared at the
  // same time points (the coarse grid), so the ratio is not polluted by where the max is sampled.
  const double coarse = 1e-2;
  double previous = 0.0;
  for (int refinement = 0; refinement < 3; ++refinement) {
    const int stride = 1 << refinement;
    const Trajectory traj = simulate(model, osc, init, coarse / stride, end_time);
    const double error = maxDisplacementError(traj, osc, init, stride);
    if (refinement > 0) {
      const double ratio = previous / error;
      EXPECT_GT(ratio, 3.5) << "h = " << coarse / stride;
      EXPECT_LT(ratio, 4.5) << "h = " << coarse / stride;
    }
    previous = error;
  }
}

TEST(SpringMassDamper, UndampedTrapezoidalRuleConservesEnergyExactly) {
  Oscillator osc;
  osc.damping_ratio = 0.0;
  const InitialState init;
  const Model model = buildModel(osc);
  // For a linear undamped oscillator the trapezoidal rule conserves E = ½mv² + ½k(x − x_eq)²
  // exactly: with Δx = h(vₙ + vₙ₊₁)/2 and m Δv = −k h (yₙ + yₙ₊₁)/2, ½mΔ(v²) = −½kΔ(y²).
  // The mechanical energy differs from it by a constant. What remains is round-off: a few ulp per
  // step over ~2000 steps, i.e. ~1e-13 relative; 1e-12 is the bar. A coarse step (ω₀h = 0.2)
  // makes the point: the discrete *frequency* is 0.3 % off (a phase error of ~1 rad by t = 40 s),
  // yet the energy has no error.
  const double h = 2e-2;
  const Trajectory traj = simulate(model, osc, init, h, 40.0);
  const double e0 = mechanicalEnergy(osc, traj.q(0, 0), traj.v(0, 0));
  const double oscillation_energy = 0.5 * osc.stiffness * init.displacement * init.displacement +
                                    0.5 * osc.mass * init.velocity * init.velocity;
  double worst = 0.0;
  for (Eigen::Index n = 0; n < traj.time.size(); ++n)
    worst = std::max(worst, std::abs(mechanicalEnergy(osc, traj.q(0, n), traj.v(0, n)) - e0));
  EXPECT_LE(worst / oscillation_energy, 1e-12);
  EXPECT_LE(worst / std::abs(e0), 1e-12);
}

}  // namespace
