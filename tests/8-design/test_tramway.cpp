// The tramway scene of docs/tramway.md, and the two charts of the bogie yaw.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/design/tramway.hpp"

using namespace mbsopt;

namespace {

struct TramwayRun {
  Scene scene;
  Trajectory trajectory;
  Eigen::MatrixXd sensors;  // rows: time points; columns: a_lat, yaw_front, yaw_rear
};

TramwayRun simulate(const TramwayDesign& design, const TramwayOptions& options, double step, double end_time) {
  TramwayRun run{tramwayScene(design, options), {}, {}};
  run.scene.settings.step = step;
  run.scene.settings.end_time = end_time;
  NewmarkIntegrator integrator(run.scene.model, run.scene.settings);
  run.trajectory = integrator.simulate(run.scene.q0, run.scene.v0);
  run.sensors = sensorHistory(run.scene.model, run.trajectory);
  return run;
}

double articulationAtEnd(const TramwayRun& run) {
  const Eigen::Index last = run.trajectory.time.size() - 1;
  return run.trajectory.q(run.scene.model.coordinate("articulation"), last);
}

}  // namespace

TEST(Tramway, SpecRunCompletesWithClosedLoopAndBoundedResponses) {
  const TramwayRun run = simulate({}, {}, 1e-3, tramway::kEndTime);
  ASSERT_EQ(run.trajectory.time.size(), 12001);
  EXPECT_NEAR(run.trajectory.time[12000], 12.0, 1e-12);
  // Position-level closure is solved by Newton to the round-off floor at every step.
  EXPECT_LE(run.trajectory.closure_error.maxCoeff(), 1e-9);
  // The driven bogie covers 3.7 m/s × 12 s. At t = 12 s both bogies are on the last straight, so the
  // arc length between them is their distance: two 4.5 m halves meeting at the articulation angle θ,
  // s₁ − s₂ = 9 cos(θ/2), an independent check of the loop closure through the track.
  const Eigen::Index last = run.trajectory.time.size() - 1;
  const double s1 = run.trajectory.q(run.scene.model.coordinate("bogie1_track"), last);
  const double s2 = run.trajectory.q(run.scene.model.coordinate("bogie2_track"), last);
  const double theta = run.trajectory.q(run.scene.model.coordinate("articulation"), last);
  EXPECT_NEAR(s1, 10.0 + 3.7 * 12.0, 1e-9);
  ASSERT_GT(s2, tramway::kFirstStraight + tramway::kRadius * std::numbers::pi / 2.0);  // on the straight
  EXPECT_NEAR(s1 - s2, tramway::kBogieSpacing * std::cos(0.5 * theta), 1e-9);
  // No step artefacts: the largest lateral acceleration stays of the order of the steady
  // centripetal value V²/R = 0.98 m/s² (a spike of 2Δκ·V/h ≈ 500 m/s² would show a broken chart).
  EXPECT_LT(run.sensors.col(0).cwiseAbs().maxCoeff(), 5.0 * 3.7 * 3.7 / tramway::kRadius);
}

// In a long arc at low speed the vehicle settles where every spring is at rest: each carbody aligned
// with its bogie, each bogie with the track tangent. The articulation is then where the two tangents
// 4.5 m from the bogie centres meet, so its angle is −2·atan(4.5/R). At speed V the centripetal loads
// on the carbodies (centres 0.5 m off the pivots) shift the equilibrium by a term ∝ V²: Richardson
// extrapolation from V and 2V removes it and must give the geometric value.
TEST(Tramway, ArticulationSettlesToTheTrackGeometryInALongArc) {
  const double half_spacing = 0.5 * tramway::kBogieSpacing;
  const double geometric = -2.0 * std::atan(half_spacing / tramway::kRadius);
  const TramwayDesign damped{246e3, 246e3, 50e3, 50e3};
  auto settled = [&](double speed) {
    TramwayOptions options;
    options.speed = speed;
    options.arc_angle = 1.5 * std::numbers::pi;
    // End with both bogies deep in the arc: bogie 1 0.5 rad before the arc's end.
    const double arc_end = tramway::kFirstStraight + tramway::kRadius * options.arc_angle;
    const double end_time = (arc_end - 0.5 * tramway::kRadius - tramway::kStartArcLength) / speed;
    return articulationAtEnd(simulate(damped, options, 5e-3, end_time));
  };
  const double slow = settled(1.0), fast = settled(2.0);
  const double extrapolated = slow - (fast - slow) / 3.0;  // a(V) = a₀ + c V²
  // The V² model is quasi-static; the remaining transient decays as exp(−ζωt) over ~60 s, so the
  // extrapolated angle must match the geometry to 0.01° and each run is at most a few tenths off.
  EXPECT_NEAR(extrapolated, geometric, 0.01 * std::numbers::pi / 180.0);
  EXPECT_NEAR(slow, geometric, 0.5 * std::numbers::pi / 180.0);
  // The centripetal shift grows with speed: |fast − geo| ≈ 4 |slow − geo|.
  EXPECT_NEAR((fast - geometric) / (slow - geometric), 4.0, 0.4);
}

// With clothoid transitions the curvature is continuous, and both charts describe the same mechanism:
// absolute bogie yaw with track guidance (default) and the spec's yaw relative to the tangent.
// Their yaw responses must agree up to discretisation error, which shrinks with h. A wrong sign in
// the guidance's generalised force on s (−κτ) makes them differ by 7e-2 rad.
TEST(Tramway, AbsoluteAndTrackRelativeChartsAgreeOnASmoothTrack) {
  auto difference = [](double step) {
    TramwayOptions absolute, relative;
    absolute.transition_length = relative.transition_length = 3.0;
    relative.chart = BogieYawChart::RelativeToTrack;
    const TramwayRun a = simulate({}, absolute, step, tramway::kEndTime);
    const TramwayRun r = simulate({}, relative, step, tramway::kEndTime);
    return (a.sensors.rightCols(2) - r.sensors.rightCols(2)).cwiseAbs().maxCoeff();
  };
  const double coarse = difference(2e-3), fine = difference(1e-3);
  EXPECT_LT(fine, coarse);
  EXPECT_LT(fine, 1e-4);  // rad; the yaw amplitudes are ~0.16 rad
}

// The spec's literal chart on the spec's track (curvature jump at the arc's ends). With the bogie yaw
// measured from the track tangent, the inertia term I(κ s̈ + κ' ṡ²) holds a Dirac in κ' = dκ/ds at
// the jump, which a piecewise track (κ' = 0 inside each segment) cannot carry. Integrated as it
// stands, the relative yaw rate stays continuous, so the bogie's absolute yaw rate jumps by Δκ·V,
// an impulse no finite force produces. The absolute chart keeps it continuous. This is why the
// absolute chart is the default; the two charts converge to different solutions on this track.
TEST(Tramway, TrackRelativeChartKicksTheBogieYawRateAtCurvatureJumps) {
  const double step = 1e-3;
  const double entry_time = (tramway::kFirstStraight - tramway::kStartArcLength) / 3.7;  // s₁ = 12 m
  auto yaw_rate_jump = [&](BogieYawChart chart) {
    TramwayOptions options;
    options.chart = chart;
    const TramwayRun run = simulate({}, options, step, 1.0);
    Workspace<double> ws(run.scene.model);
    const FrameIndex bogie = run.scene.model.frame("bogie1_yaw");
    auto yaw_rate = [&](Eigen::Index k) {
      const Eigen::VectorXd q = run.trajectory.q.col(k), v = run.trajectory.v.col(k), a = run.trajectory.a.col(k);
      forwardKinematics(run.scene.model, ws, q, v, a, KinematicsLevel::Velocity);
      return ws.angular_velocity[static_cast<std::size_t>(bogie)].z();
    };
    const auto before = static_cast<Eigen::Index>(std::floor(entry_time / step));
    return yaw_rate(before + 1) - yaw_rate(before);
  };
  const double kick = 3.7 / tramway::kRadius;  // Δκ·V [rad/s]
  // Physical: over one step the yaw rate changes by h·α, α = (guidance torque)/I ≪ kick/h.
  EXPECT_LT(std::abs(yaw_rate_jump(BogieYawChart::Absolute)), 0.02 * kick);
  EXPECT_NEAR(yaw_rate_jump(BogieYawChart::RelativeToTrack), kick, 0.05 * kick);
}

TEST(Tramway, AccelerationsAtRestAreTheRatePassAtZeroSpeedToTheBit) {
  // frameAccelerationsAtRest drops the terms of (20)-(21) in q̇, which are exact zeros at q̇ = 0: on
  // the tram's offsets, revolute joints and curve sliders (in the curve, where the track's biases
  // are not zero) it must give frameRates' values at q̇ = 0 to the last bit, in double and in AD
  // (geometry seeded in q, so the derivatives are not zero either).
  const TramwayRun run = simulate({}, {}, 1e-3, 4.0);
  const Model& model = run.scene.model;
  const Eigen::Index k = run.trajectory.time.size() - 1;
  const Eigen::VectorXd q = run.trajectory.q.col(k);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(q.size());
  Eigen::VectorXd a(q.size());
  for (Eigen::Index i = 0; i < a.size(); ++i) a[i] = 0.3 * static_cast<double>(i + 1) - 1.1;  // any accelerations

  Workspace<double> rates(model), rest(model);
  forwardKinematics(model, rates, q, zero, a, KinematicsLevel::Acceleration);
  frameGeometry(model, rest, q);
  frameAccelerationsAtRest(model, rest, a);
  for (std::size_t f = 0; f < rates.rotation.size(); ++f) {
    EXPECT_EQ(rest.angular_velocity[f], Eigen::Vector3d::Zero()) << "frame " << f;
    EXPECT_EQ(rest.velocity[f], Eigen::Vector3d::Zero()) << "frame " << f;
    EXPECT_EQ(rest.angular_acceleration[f], rates.angular_acceleration[f]) << "frame " << f;
    EXPECT_EQ(rest.acceleration[f], rates.acceleration[f]) << "frame " << f;
  }

  VectorX<AdScalar> q_ad, zero_ad, a_ad;
  seedVector(q, 0, 0, q.size(), q_ad);
  seedVector(zero, 0, 0, 0, zero_ad);
  seedVector(a, 0, 0, 0, a_ad);
  Workspace<AdScalar> rates_ad(model), rest_ad(model);
  forwardKinematics(model, rates_ad, q_ad, zero_ad, a_ad, KinematicsLevel::Acceleration);
  forwardKinematics(model, rest_ad, q_ad, zero_ad, a_ad, KinematicsLevel::Velocity);  // geometry and joint axes
  frameAccelerationsAtRest(model, rest_ad, a_ad);
  bool seeded = false;
  for (std::size_t f = 0; f < rates_ad.rotation.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const AdScalar& expected = rates_ad.acceleration[f][i];
      EXPECT_EQ(rest_ad.acceleration[f][i].value(), expected.value()) << "frame " << f;
      EXPECT_EQ(rest_ad.acceleration[f][i].derivatives(), expected.derivatives()) << "frame " << f;
      EXPECT_EQ(rest_ad.angular_acceleration[f][i].derivatives(), rates_ad.angular_acceleration[f][i].derivatives());
      seeded = seeded || !expected.derivatives().isZero(0.0);
    }
  EXPECT_TRUE(seeded) << "no acceleration depends on q: the AD comparison checks nothing";
}
