// Track geometry (straight–clothoid–arc–clothoid–straight) against closed forms and an independent
// quadrature, and the kinematics of a driven curve slider through simulate + sensorHistory against
// the closed-form motion of a point on a circle.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/track.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Eigen::Vector3d unitTangent(double heading) { return {std::cos(heading), std::sin(heading), 0.0}; }
Eigen::Vector3d unitNormal(double heading) { return {-std::sin(heading), std::cos(heading), 0.0}; }

// =====================================================================================================
// (a) Track geometry
// =====================================================================================================

/// A straight–clothoid–arc–clothoid–straight track described by its parameters, with the closed-form
/// heading ψ(s), curvature κ(s) and dκ/ds written independently of Track. `turn` = +1 turns left,
/// −1 turns right.
struct TransitionCurve {
  double turn;
  Eigen::Vector3d origin{1.5, -2.0, 0.25};
  double heading0 = 0.3;
  double first_straight = 6.0;
  double clothoid_length = 10.0;
  double radius = 15.0;
  double arc_angle = 0.8;  // magnitude [rad]
  double last_straight = 7.0;

  double kappa() const { return turn / radius; }  // signed curvature of the arc
  double arcLength() const { return arc_angle * radius; }
  /// Arc lengths at which the five segments start, and the total length.
  std::vector<double> breaks() const {
    std::vector<double> b{0.0, first_straight};
    b.push_back(b.back() + clothoid_length);
    b.push_back(b.back() + arcLength());
    b.push_back(b.back() + clothoid_length);
    b.push_back(b.back() + last_straight);
    return b;
  }
  double totalLength() const { return breaks().back(); }

  Track build() const {
    Track track(origin, heading0);
    track.straight(first_straight)
        .clothoid(clothoid_length, kappa())
        .arc(radius, turn * arc_angle)
        .clothoid(clothoid_length, 0.0)
        .straight(last_straight);
    return track;
  }

  /// Index of the segment holding s (right-continuous at the junctions, like Track).
  int segmentOf(double s) const {
    const std::vector<double> b = breaks();
    int k = 0;
    while (k < 4 && s >= b[static_cast<std::size_t>(k + 1)]) ++k;
    return k;
  }

  double curvature(double s) const {
    const std::vector<double> b = breaks();
    const double sigma = s - b[static_cast<std::size_t>(segmentOf(s))];
    switch (segmentOf(s)) {
      case 1: return kappa() * sigma / clothoid_length;
      case 2: return kappa();
      case 3: return kappa() * (1.0 - sigma / clothoid_length);
      default: return 0.0;
    }
  }

  double curvatureDerivative(double s) const {
    switch (segmentOf(s)) {
      case 1: return kappa() / clothoid_length;
      case 3: return -kappa() / clothoid_length;
      default: return 0.0;
    }
  }

  /// ψ(s) = ψ₀ + ∫κ: each clothoid turns κL/2, the arc κ·(arc length).
  double heading(double s) const {
    const std::vector<double> b = breaks();
    const double Lc = clothoid_length;
    const double sigma = s - b[static_cast<std::size_t>(segmentOf(s))];
    const double after_clothoid = heading0 + 0.5 * kappa() * Lc;
    const double after_arc = after_clothoid + kappa() * arcLength();
    switch (segmentOf(s)) {
      case 0: return heading0;
      case 1: return heading0 + 0.5 * kappa() * sigma * sigma / Lc;
      case 2: return after_clothoid + kappa() * sigma;
      case 3: return after_arc + kappa() * (sigma - 0.5 * sigma * sigma / Lc);
      default: return after_arc + 0.5 * kappa() * Lc;
    }
  }

  /// Sample arc lengths strictly inside segment k, at least `margin` away from its ends.
  std::vector<double> interiorSamples(int k, int count, double margin) const {
    const std::vector<double> b = breaks();
    const double a = b[static_cast<std::size_t>(k)] + margin, e = b[static_cast<std::size_t>(k + 1)] - margin;
    std::vector<double> s;
    for (int i = 0; i < count; ++i) s.push_back(a + (e - a) * (i + 0.5) / count);
    return s;
  }
};

/// Adaptive Simpson quadrature of a 2-vector integrand with Richardson extrapolation. The error
/// test is per unit length (|S₂ − S₁| ≤ 15·tol·width), so the total error is ≲ tol·(b − a) without
/// the tolerance collapsing to round-off at deep levels.
class AdaptiveSimpson {
 public:
  using Integrand = std::function<Eigen::Vector2d(double)>;
  AdaptiveSimpson(Integrand f, double tolerance_per_length) : f_(std::move(f)), tol_(tolerance_per_length) {}

  Eigen::Vector2d integrate(double a, double b) const {
    const Eigen::Vector2d fa = f_(a), fm = f_(0.5 * (a + b)), fb = f_(b);
    return refine(a, b, fa, fm, fb, simpson(a, b, fa, fm, fb), 0);
  }

 private:
  static Eigen::Vector2d simpson(double a, double b, const Eigen::Vector2d& fa, const Eigen::Vector2d& fm,
                                 const Eigen::Vector2d& fb) {
    return (b - a) / 6.0 * (fa + 4.0 * fm + fb);
  }
  Eigen::Vector2d refine(double a, double b, const Eigen::Vector2d& fa, const Eigen::Vector2d& fm,
                         const Eigen::Vector2d& fb, const Eigen::Vector2d& whole, int depth) const {
    const double m = 0.5 * (a + b);
    const Eigen::Vector2d flm = f_(0.5 * (a + m)), frm = f_(0.5 * (m + b));
    const Eigen::Vector2d left = simpson(a, m, fa, flm, fm), right = simpson(m, b, fm, frm, fb);
    const Eigen::Vector2d difference = left + right - whole;
    if (depth >= 40 || difference.cwiseAbs().maxCoeff() <= 15.0 * tol_ * (b - a))
      return left + right + difference / 15.0;
    return refine(a, m, fa, flm, fm, left, depth + 1) + refine(m, b, fm, frm, fb, right, depth + 1);
  }

  Integrand f_;
  double tol_;
};

/// r(s) = r₀ + ∫₀ˢ (cos ψ, sin ψ) dσ with the closed-form ψ, integrated segment by segment (the
/// integrand is smooth inside each segment) by adaptive Simpson to 1e-14 per metre.
Eigen::Vector3d referencePosition(const TransitionCurve& curve, double s) {
  const AdaptiveSimpson quadrature(
      [&](double x) { return Eigen::Vector2d(std::cos(curve.heading(x)), std::sin(curve.heading(x))); }, 1e-14);
  const std::vector<double> b = curve.breaks();
  Eigen::Vector3d r = curve.origin;
  for (std::size_t k = 0; k + 1 < b.size() && b[k] < s; ++k) {
    const Eigen::Vector2d piece = quadrature.integrate(b[k], std::min(s, b[k + 1]));
    r.head<2>() += piece;
  }
  return r;
}

class TrackGeometryTest : public ::testing::TestWithParam<double> {
 protected:
  TransitionCurve curve{GetParam()};
  Track track = curve.build();

  /// 9 samples inside each of the five segments, plus the junctions themselves.
  std::vector<double> samples(double margin) const {
    std::vector<double> s;
    for (int k = 0; k < 5; ++k)
      for (double x : curve.interiorSamples(k, 9, margin)) s.push_back(x);
    for (double x : curve.breaks()) s.push_back(x);
    return s;
  }
};

TEST_P(TrackGeometryTest, SegmentLayoutMatchesTheDescription) {
  ASSERT_EQ(track.segments().size(), 5u);
  // Lengths are sums of the given lengths and R·θ: exact to a few ulps of the total.
  EXPECT_NEAR(track.length(), curve.totalLength(), 4.0 * kEps * curve.totalLength());
}

TEST_P(TrackGeometryTest, HeadingCurvatureAndItsDerivativeMatchClosedForms) {
  // ψ, κ, κ' are polynomials in σ evaluated in a handful of flops: agreement to round-off of ψ (~2 rad).
  for (double s : samples(0.0)) {
    const TrackPoint p = track.at(s);
    EXPECT_NEAR(p.heading, curve.heading(s), 1e-13) << "s = " << s;
    EXPECT_NEAR(p.curvature, curve.curvature(s), 1e-15) << "s = " << s;
    EXPECT_NEAR(p.curvature_derivative, curve.curvatureDerivative(s), 1e-15) << "s = " << s;
    EXPECT_NEAR((p.tangent() - unitTangent(curve.heading(s))).norm(), 0.0, 1e-13) << "s = " << s;
    EXPECT_NEAR((p.normal() - unitNormal(curve.heading(s))).norm(), 0.0, 1e-13) << "s = " << s;
  }
}

TEST_P(TrackGeometryTest, PositionAgreesWithIndependentQuadratureOfTheHeading) {
  // The reference integrates (cos ψ, sin ψ) to ≲ 1e-14 per metre (≲ 6e-13 m over the track); Track's
  // Gauss-Legendre panels are exact to round-off. 1e-12 m bounds both with margin.
  for (double s : samples(0.0)) {
    const Eigen::Vector3d expected = referencePosition(curve, s);
    EXPECT_LT((track.at(s).position - expected).norm(), 1e-12) << "s = " << s;
  }
}

TEST_P(TrackGeometryTest, ArcPointsLieOnTheCircleOfRadiusR) {
  // Centre of the circle, closed form from the arc's start: c = r_a + n(ψ_a)/κ (n points left, so
  // towards the centre for a left turn and away from it for a right turn). Every point of the arc
  // is then c − n(ψ(s))/κ; Track's chord (sin θ t_a + (1 − cos θ) n_a)/κ, θ = κσ, reproduces this to
  // round-off of |r| ~ 30 m (~1e-14), and the reference start r_a carries ≲ 6e-13 m: tolerance 1e-12 m.
  const std::vector<double> b = curve.breaks();
  const double arc_start = b[2], arc_end = b[3];
  const Eigen::Vector3d centre = referencePosition(curve, arc_start) + unitNormal(curve.heading(arc_start)) / curve.kappa();
  std::vector<double> on_arc = curve.interiorSamples(2, 25, 0.0);
  on_arc.push_back(arc_start);
  on_arc.push_back(arc_end);
  for (double s : on_arc) {
    const Eigen::Vector3d r = track.at(s).position;
    EXPECT_NEAR((r - centre).norm(), curve.radius, 1e-12) << "s = " << s;
    EXPECT_LT((r - (centre - unitNormal(curve.heading(s)) / curve.kappa())).norm(), 1e-12) << "s = " << s;
  }
}

TEST_P(TrackGeometryTest, PositionDerivativeIsTheUnitTangent) {
  // Central difference with step h: truncation ≤ h²/6·max|r'''|, r''' = κ'n − κ²t (κ is continuous,
  // so r'' is Lipschitz and the bound holds across junctions too); round-off ≤ 2·(2ε·max|r|)/(2h).
  // h = 1e-4 is near the optimum (3ε|r|/|r'''|)^(1/3); the tolerance is twice the sum (~5e-10).
  const double h = 1e-4;
  const double third_derivative = std::abs(curve.kappa()) / curve.clothoid_length + curve.kappa() * curve.kappa();
  const double largest_position = curve.origin.norm() + curve.totalLength();
  const double tolerance = 2.0 * (h * h / 6.0 * third_derivative + 2.0 * kEps * largest_position / h);
  for (double s : samples(0.0)) {
    const Eigen::Vector3d slope = (track.at(s + h).position - track.at(s - h).position) / (2.0 * h);
    EXPECT_LT((slope - track.at(s).tangent()).norm(), tolerance) << "s = " << s << ", tolerance " << tolerance;
  }
}

TEST_P(TrackGeometryTest, HeadingDerivativeIsTheCurvature) {
  // Inside a segment ψ is quadratic in s, so the central difference of ψ is exact up to round-off
  // ≈ 2ε·max|ψ|/(2h), and that of κ (linear) too; tolerance 4× that (~1e-12). Stencils stay 2h
  // clear of the junctions, where κ' jumps and ψ is only C².
  const double h = 1e-3;
  const double largest_heading = std::abs(curve.heading0) + curve.arc_angle + std::abs(curve.kappa()) * curve.clothoid_length;
  const double tolerance = 4.0 * kEps * largest_heading / h;
  for (int k = 0; k < 5; ++k) {
    for (double s : curve.interiorSamples(k, 9, 2.0 * h)) {
      const TrackPoint p = track.at(s);
      EXPECT_NEAR((track.at(s + h).heading - track.at(s - h).heading) / (2.0 * h), p.curvature, tolerance)
          << "s = " << s;
      EXPECT_NEAR((track.at(s + h).curvature - track.at(s - h).curvature) / (2.0 * h), p.curvature_derivative,
                  tolerance)
          << "s = " << s;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(LeftAndRightTurns, TrackGeometryTest, ::testing::Values(1.0, -1.0),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return info.param > 0.0 ? std::string("Left") : std::string("Right");
                         });

// =====================================================================================================
// (b) A driven curve slider on a long arc
// =====================================================================================================

/// Prescribed arc length s(t) = s₀ + v₀t + a₀t²/2 on a straight–arc–straight track whose arc
/// (radius R, signed curvature κ) holds the slider for the whole run.
struct ArcRide {
  std::string name;
  double turn;                     // +1 left, −1 right
  double initial_speed;            // v₀ [m/s]
  double tangential_acceleration;  // a₀ [m/s²]

  static constexpr double kRadius = 20.0;
  static constexpr double kLeadIn = 5.0;    // straight before the arc [m]
  static constexpr double kArcAngle = 2.0;  // [rad], arc length 40 m
  static constexpr double kStart = 8.0;     // s₀, on the arc [m]
  static constexpr double kEndTime = 8.0;   // [s]; s(t) ≤ 32 m < 45 m in every case
  static constexpr double kHeading0 = 0.4;
  static inline const Eigen::Vector3d kOrigin{3.0, -1.0, 0.5};

  double kappa() const { return turn / kRadius; }
  double s(double t) const { return kStart + initial_speed * t + 0.5 * tangential_acceleration * t * t; }
  double speed(double t) const { return initial_speed + tangential_acceleration * t; }
  double heading(double t) const { return kHeading0 + kappa() * (s(t) - kLeadIn); }

  Track track() const {
    Track track(kOrigin, kHeading0);
    track.straight(kLeadIn).arc(kRadius, turn * kArcAngle).straight(10.0);
    return track;
  }

  /// Centre of the arc: the arc starts at r_a = r₀ + L·t(ψ₀) and n/κ points from it to the centre.
  Eigen::Vector3d centre() const { return kOrigin + kLeadIn * unitTangent(kHeading0) + unitNormal(kHeading0) / kappa(); }

  // Closed forms of a point moving on a circle, in ground axes.
  Eigen::Vector3d position(double t) const { return centre() - unitNormal(heading(t)) / kappa(); }
  Eigen::Vector3d velocity(double t) const { return speed(t) * unitTangent(heading(t)); }
  Eigen::Vector3d acceleration(double t) const {
    return tangential_acceleration * unitTangent(heading(t)) + kappa() * speed(t) * speed(t) * unitNormal(heading(t));
  }
  // The slider frame's axes are (t, n, z): there v = (ṡ, 0, 0) and a = (s̈, κṡ², 0).
  Eigen::Vector3d velocityInSliderAxes(double t) const { return {speed(t), 0.0, 0.0}; }
  Eigen::Vector3d accelerationInSliderAxes(double t) const {
    return {tangential_acceleration, kappa() * speed(t) * speed(t), 0.0};
  }
};

void PrintTo(const ArcRide& ride, std::ostream* out) { *out << ride.name; }

/// One sensed vector: a quantity of the slider-frame origin in ground or slider axes (3 sensors).
struct SensedVector {
  std::string name;
  Derivative quantity;
  bool slider_axes;
  Eigen::Vector3d (ArcRide::*expected)(double) const;
};

const std::vector<SensedVector>& sensedVectors() {
  static const std::vector<SensedVector> vectors = {
      {"position_ground", Derivative::Position, false, &ArcRide::position},
      {"velocity_ground", Derivative::Velocity, false, &ArcRide::velocity},
      {"acceleration_ground", Derivative::Acceleration, false, &ArcRide::acceleration},
      {"velocity_slider", Derivative::Velocity, true, &ArcRide::velocityInSliderAxes},
      {"acceleration_slider", Derivative::Acceleration, true, &ArcRide::accelerationInSliderAxes},
  };
  return vectors;
}

// The coordinate is driven, so s, ṡ, s̈ are the polynomial's exact values: no integration error
// enters (a Newmark-integrated coordinate would be off by O(h²) ~ 1e-5 here). What remains is
// round-off in |r| ~ 40 m, R = 20 m and ṡ² ≲ 50 (~1e-13): tolerance 1e-10.
constexpr double kKinematicTolerance = 1e-10;

/// Builds the slider model (a body on the slider frame, its arc length driven), simulates it with
/// Newmark and evaluates every sensor at every time point.
class DrivenCurveSliderTest : public ::testing::TestWithParam<ArcRide> {
 protected:
  void SetUp() override {
    const ArcRide& ride = GetParam();
    slider_ = model_.addCurveSlider("slider", Model::ground, model_.addTrack("rail", ride.track()));
    model_.addBody("cart", slider_, 50.0, Eigen::Vector3d(0.3, 0.1, 0.0), 4.0 * Eigen::Matrix3d::Identity());
    model_.drive("slider",
                 TimeFunction::polynomial({ArcRide::kStart, ride.initial_speed, 0.5 * ride.tangential_acceleration}));
    for (const SensedVector& vector : sensedVectors())
      for (int c = 0; c < 3; ++c)
        model_.addSensor(vector.name + "_" + "xyz"[c],
                         PointSensor{slider_, Eigen::Vector3d::Zero(), vector.quantity,
                                     vector.slider_axes ? slider_ : Model::ground, c});
    NewmarkSettings settings;
    settings.step = 1e-2;
    settings.end_time = ArcRide::kEndTime;
    const Eigen::Index n = model_.coordinateCount();
    trajectory_ = NewmarkIntegrator(model_, settings).simulate(Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
    history_ = sensorHistory(model_, trajectory_);
    ASSERT_EQ(history_.rows(), std::lround(ArcRide::kEndTime / settings.step) + 1);
    ASSERT_LT(ride.s(ArcRide::kEndTime), ArcRide::kLeadIn + ArcRide::kArcAngle * ArcRide::kRadius)
        << "the ride must stay on the arc";
  }

  /// The sensed vector `name` at time point k.
  Eigen::Vector3d sensed(const std::string& name, Eigen::Index k) const {
    const auto column = static_cast<Eigen::Index>(model_.sensor(name + "_x"));
    return history_.row(k).segment<3>(column).transpose();
  }

  Model model_;
  FrameIndex slider_ = -1;
  Trajectory trajectory_;
  Eigen::MatrixXd history_;
};

TEST_P(DrivenCurveSliderTest, EverySensedComponentMatchesTheClosedForm) {
  const ArcRide& ride = GetParam();
  for (Eigen::Index k = 0; k < history_.rows(); ++k) {
    const double t = trajectory_.time[k];
    for (const SensedVector& vector : sensedVectors()) {
      const Eigen::Vector3d expected = (ride.*vector.expected)(t);
      const Eigen::Vector3d actual = sensed(vector.name, k);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(actual[c], expected[c], kKinematicTolerance) << vector.name << "[" << c << "] at t = " << t;
    }
  }
}

TEST_P(DrivenCurveSliderTest, OnTheCircleWithSpeedVAndCentripetalAccelerationVSquaredOverR) {
  // Frame-independent restatement from the ground-axes sensors: |r − c| = R, |v| = ṡ, v ⟂ (r − c),
  // a·(c − r)/R = ṡ²/R (towards the centre), a·v/|v| = s̈ (zero at constant speed).
  const ArcRide& ride = GetParam();
  for (Eigen::Index k = 0; k < history_.rows(); ++k) {
    const double t = trajectory_.time[k];
    const Eigen::Vector3d radial = sensed("position_ground", k) - ride.centre();
    const Eigen::Vector3d v = sensed("velocity_ground", k);
    const Eigen::Vector3d a = sensed("acceleration_ground", k);
    const double speed = ride.speed(t);
    EXPECT_NEAR(radial.norm(), ArcRide::kRadius, kKinematicTolerance) << "t = " << t;
    EXPECT_NEAR(v.norm(), speed, kKinematicTolerance) << "t = " << t;
    EXPECT_NEAR(v.dot(radial) / ArcRide::kRadius, 0.0, kKinematicTolerance) << "t = " << t;
    EXPECT_NEAR(-a.dot(radial) / ArcRide::kRadius, speed * speed / ArcRide::kRadius, kKinematicTolerance) << "t = " << t;
    EXPECT_NEAR(a.dot(v) / speed, ride.tangential_acceleration, kKinematicTolerance) << "t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(ConstantSpeedAndConstantAcceleration, DrivenCurveSliderTest,
                         ::testing::Values(ArcRide{"ConstantSpeedLeft", 1.0, 3.0, 0.0},
                                           ArcRide{"ConstantSpeedRight", -1.0, 3.0, 0.0},
                                           ArcRide{"AcceleratingLeft", 1.0, 1.0, 0.5},
                                           ArcRide{"AcceleratingRight", -1.0, 1.0, 0.5}),
                         [](const ::testing::TestParamInfo<ArcRide>& info) { return info.param.name; });

}  // namespace
}  // namespace mbsopt
