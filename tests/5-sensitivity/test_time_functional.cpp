// Time functionals on the integrator's grid: their values against closed-form integrals (with the
// trapezoidal rule's error bound), and their gradients with respect to the samples against
// central differences (the functionals are piecewise polynomial in the samples, so the
// differences are exact up to round-off away from the kinks).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "mbsopt/sensitivity/time_functional.hpp"

namespace mbsopt {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::VectorXd grid(double end, int intervals) { return Eigen::VectorXd::LinSpaced(intervals + 1, 0.0, end); }

Eigen::VectorXd sine(const Eigen::VectorXd& t) { return t.array().sin().matrix(); }

// Trapezoidal rule: |error| ≤ (b − a) h² max|f''| / 12.
TEST(TimeFunctional, IntegralIsTheTrapezoidalRuleWithItsErrorBound) {
  for (const int intervals : {100, 1000}) {
    const Eigen::VectorXd t = grid(kPi, intervals);
    const double h = kPi / intervals;
    const TimeFunctionalValue f = evaluateTimeFunctional(TimeMeasure::Integral, t, sine(t));
    EXPECT_LE(std::abs(f.value - 2.0), kPi * h * h / 12.0);
    EXPECT_GE(std::abs(f.value - 2.0), 0.5 * kPi * h * h / 12.0);  // and second order, not better
  }
}

// ∫₀^{2π} ⟨sin⟩ = 2 and ∫₀^{2π} ⟨sin⟩² = π/2; the kink at π is a grid point, so each smooth piece
// keeps the bound ((sin)'' ≤ 1, (sin²)'' ≤ 2).
TEST(TimeFunctional, PositivePartsOfASine) {
  const int intervals = 2000;
  const double h = 2.0 * kPi / intervals;
  const Eigen::VectorXd t = grid(2.0 * kPi, intervals);
  EXPECT_NEAR(evaluateTimeFunctional(TimeMeasure::PositivePart, t, sine(t)).value, 2.0, kPi * h * h / 12.0);
  EXPECT_NEAR(evaluateTimeFunctional(TimeMeasure::SquaredPositivePart, t, sine(t)).value, kPi / 2.0,
              kPi * h * h / 6.0);
  // A history that never exceeds zero is feasible: value and gradient vanish (the paper's form).
  const TimeFunctionalValue feasible =
      evaluateTimeFunctional(TimeMeasure::PositivePart, t, (sine(t).array() - 1.5).matrix());
  EXPECT_EQ(feasible.value, 0.0);
  EXPECT_EQ(feasible.gradient.norm(), 0.0);
}

// The time mean of e^{ρ sin t} over a period is the modified Bessel function I₀(ρ), and the
// trapezoidal rule is spectrally accurate for a periodic analytic integrand: KS = ln I₀(ρ) / ρ.
TEST(TimeFunctional, KsAggregateOfASineIsTheBesselClosedForm) {
  const Eigen::VectorXd t = grid(2.0 * kPi, 400);
  double previous = -1.0;
  for (const double rho : {1.0, 5.0, 50.0, 500.0}) {
    const double ks = evaluateTimeFunctional(TimeMeasure::KsAggregate, t, sine(t), rho).value;
    EXPECT_NEAR(ks, std::log(std::cyl_bessel_i(0.0, rho)) / rho, 1e-12 * (1.0 + std::abs(ks))) << rho;
    EXPECT_LE(ks, 1.0);       // below the maximum,
    EXPECT_GT(ks, previous);  // approaching it as ρ grows
    previous = ks;
  }
  EXPECT_GT(previous, 0.99);
}

// The trapezoidal rule is exact for a trigonometric polynomial of degree below the number of
// intervals over whole periods, so the RMS of sin over two periods is 1/√2 to round-off, on any
// uniform grid of at least three intervals per period; and that of a constant its absolute value.
TEST(TimeFunctional, RootMeanSquareOfASineOverWholePeriods) {
  for (const int intervals : {6, 50, 1000}) {
    const Eigen::VectorXd t = grid(4.0 * kPi, intervals);
    EXPECT_NEAR(evaluateTimeFunctional(TimeMeasure::RootMeanSquare, t, sine(t)).value, std::sqrt(0.5), 1e-15) << intervals;
  }
  const Eigen::VectorXd t = grid(1.0, 10);
  EXPECT_NEAR(evaluateTimeFunctional(TimeMeasure::RootMeanSquare, t, Eigen::VectorXd::Constant(11, -0.3)).value, 0.3,
              1e-16);
  const TimeFunctionalValue zero = evaluateTimeFunctional(TimeMeasure::RootMeanSquare, t, Eigen::VectorXd::Zero(11));
  EXPECT_EQ(zero.value, 0.0);
  EXPECT_TRUE(zero.gradient.allFinite());
}

TEST(TimeFunctional, MaxAndFinalValue) {
  const Eigen::VectorXd t = grid(1.0, 4);
  const Eigen::VectorXd g = (Eigen::VectorXd(5) << 0.1, 0.7, -0.2, 0.3, -0.4).finished();
  const TimeFunctionalValue max = evaluateTimeFunctional(TimeMeasure::GridMax, t, g);
  EXPECT_EQ(max.value, 0.7);
  EXPECT_EQ(max.gradient, (Eigen::VectorXd(5) << 0, 1, 0, 0, 0).finished());
  const TimeFunctionalValue final_value = evaluateTimeFunctional(TimeMeasure::FinalValue, t, g);
  EXPECT_EQ(final_value.value, -0.4);
  EXPECT_EQ(final_value.gradient[4], 1.0);
}

// On a non-uniform grid with samples away from zero, every functional's gradient is the central
// difference of its value, sample by sample (δ = 1e-6: truncation zero or O(δ²), round-off 1e-10).
TEST(TimeFunctional, GradientsAreTheDerivativesOfTheDiscreteValues) {
  std::mt19937 engine(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::VectorXd t(30), g(30);
  t[0] = 0.0;
  for (Eigen::Index k = 1; k < t.size(); ++k) t[k] = t[k - 1] + 0.05 + 0.1 * uniform(engine);
  for (Eigen::Index k = 0; k < g.size(); ++k) g[k] = (k % 3 == 0 ? -1.0 : 1.0) * (0.2 + uniform(engine));
  for (const TimeMeasure measure : {TimeMeasure::Integral, TimeMeasure::PositivePart,
                                    TimeMeasure::SquaredPositivePart, TimeMeasure::KsAggregate,
                                    TimeMeasure::GridMax, TimeMeasure::FinalValue, TimeMeasure::RootMeanSquare}) {
    const TimeFunctionalValue f = evaluateTimeFunctional(measure, t, g, 3.0);
    const double delta = 1e-6;
    for (Eigen::Index k = 0; k < g.size(); ++k) {
      Eigen::VectorXd up = g, down = g;
      up[k] += delta;
      down[k] -= delta;
      const double difference = (evaluateTimeFunctional(measure, t, up, 3.0).value -
                                 evaluateTimeFunctional(measure, t, down, 3.0).value) /
                                (2.0 * delta);
      EXPECT_NEAR(f.gradient[k], difference, 1e-8) << "measure " << static_cast<int>(measure) << ", sample " << k;
    }
  }
}

TEST(TimeFunctional, RefusesBadInput) {
  const Eigen::VectorXd t = grid(1.0, 2);
  EXPECT_THROW(evaluateTimeFunctional(TimeMeasure::Integral, t, Eigen::VectorXd::Zero(2)), std::invalid_argument);
  EXPECT_THROW(evaluateTimeFunctional(TimeMeasure::KsAggregate, t, Eigen::VectorXd::Zero(3), 0.0),
               std::invalid_argument);
  Eigen::VectorXd nan = Eigen::VectorXd::Zero(3);
  nan[1] = std::nan("");
  EXPECT_THROW(evaluateTimeFunctional(TimeMeasure::Integral, t, nan), std::invalid_argument);
}

}  // namespace
}  // namespace mbsopt
