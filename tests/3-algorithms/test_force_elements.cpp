// Force elements and sensors against closed forms: joint actuation, guidance spring towards a moving
// target, point-to-point spring-damper, rotational damper, driven coordinates, joint and
// relative-angle sensors.
#include <gtest/gtest.h>

#include <cmath>

#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/newmark.hpp"

using namespace mbsopt;

namespace {

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX(), kZ = Eigen::Vector3d::UnitZ();
const Eigen::Matrix3d kSmallInertia = 1e-3 * Eigen::Matrix3d::Identity();

Trajectory run(const Model& model, double step, double end_time, Eigen::VectorXd q0, Eigen::VectorXd v0) {
  NewmarkSettings settings;
  settings.step = step;
  settings.end_time = end_time;
  NewmarkIntegrator integrator(model, settings);
  return integrator.simulate(q0, v0);
}

}  // namespace

// m ẍ = F0 + F1 t. The trapezoidal rule integrates a quadratic x(t) exactly, so a constant force gives
// x = F0 t²/(2m) to round-off; the linear part makes x cubic, reproduced with an O(h²) error.
TEST(ForceElements, JointActuationAcceleratesAMassAsNewtonSays) {
  const double mass = 2.0, f0 = 3.0, f1 = 0.5;
  auto trajectory = [&](double force_rate, double step) {
    Model model;
    const FrameIndex slider = model.addPrismatic("slider", Model::ground, kX);
    model.addBody("block", slider, mass, Eigen::Vector3d::Zero(), kSmallInertia);
    model.addJointActuation("push", "slider", TimeFunction::polynomial({f0, force_rate}));
    return run(model, step, 2.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
  };
  const Trajectory constant = trajectory(0.0, 0.01);
  for (Eigen::Index k = 0; k < constant.time.size(); ++k) {
    const double t = constant.time[k];
    EXPECT_NEAR(constant.q(0, k), f0 * t * t / (2 * mass), 1e-12);
    EXPECT_NEAR(constant.v(0, k), f0 * t / mass, 1e-12);
    EXPECT_NEAR(constant.a(0, k), f0 / mass, 1e-12);
  }
  auto final_error = [&](double step) {
    const Trajectory ramp = trajectory(f1, step);
    const double t = 2.0;
    return std::abs(ramp.q(0, ramp.time.size() - 1) - (f0 * t * t / 2 + f1 * t * t * t / 6) / mass);
  };
  const double coarse = final_error(0.02), fine = final_error(0.01);
  EXPECT_GT(coarse, 1e-9);  // the cubic part is not integrated exactly...
  EXPECT_NEAR(coarse / fine, 4.0, 0.2);  // ...but to second order
}

// I q̈ = −k (q − r) − c (q̇ − ṙ) with an accelerating target r = ½αt²: the error e = q − r obeys
// I ë + c ė + k e = −Iα, so after the transient (ζ = 0.5, decay e^{−ζωt}) the rotor lags by the
// constant Iα/k at the target's rate. The trapezoidal rule reproduces that quadratic exactly.
TEST(ForceElements, GuidanceSpringFollowsAnAcceleratingTargetWithTheInertialLag) {
  const double inertia = 2.0, k = 200.0, c = 20.0, target_acceleration = 3.0;
  Model model;
  const FrameIndex rotor = model.addRevolute("rotor", Model::ground, kZ);
  model.addBody("wheel", rotor, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, inertia).asDiagonal());
  model.addGuidanceSpring("guidance", "rotor", k, c, TimeFunction::polynomial({0.0, 0.0, 0.5 * target_acceleration}));
  const Trajectory trajectory = run(model, 1e-3, 8.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
  const Eigen::Index last = trajectory.time.size() - 1;
  const double t = trajectory.time[last];
  // Transient ≤ (Iα/k) e^{−ζωt} with ω = 10, ζ = 0.5, t = 8: 3e-2 · 4e-18.
  const double lag = inertia * target_acceleration / k;
  EXPECT_NEAR(trajectory.q(0, last), 0.5 * target_acceleration * t * t - lag, 1e-9);
  EXPECT_NEAR(trajectory.v(0, last), target_acceleration * t, 1e-9);
}

// A point-to-point spring-damper between a ground point and a block on a prismatic joint along the
// spring's line is a linear oscillator: x(t) = x_eq + A e^{−ζωt} cos(ω_d t) + ..., compared with the
// trapezoidal rule's own discrete solution (frequency error ω³h²/12), so the bound is tight.
TEST(ForceElements, PointSpringDamperAlongItsLineIsALinearOscillator) {
  const double mass = 1.5, k = 600.0, c = 3.0, rest = 0.8, anchor = -2.0, x0 = 0.3;
  Model model;
  const FrameIndex slider = model.addPrismatic("slider", Model::ground, kX);
  model.addBody("block", slider, mass, Eigen::Vector3d::Zero(), kSmallInertia);
  model.addPointSpringDamper("spring", Model::ground, anchor * kX, slider, Eigen::Vector3d::Zero(), k, c, rest);
  const double equilibrium = anchor + rest;
  Eigen::VectorXd q0(1);
  q0 << equilibrium + x0;
  const double step = 1e-4;
  const Trajectory trajectory = run(model, step, 1.0, q0, Eigen::VectorXd::Zero(1));
  const double omega = std::sqrt(k / mass), zeta = c / (2 * std::sqrt(k * mass));
  const double damped = omega * std::sqrt(1 - zeta * zeta);
  double worst = 0.0;
  for (Eigen::Index j = 0; j < trajectory.time.size(); ++j) {
    const double t = trajectory.time[j];
    const double exact = equilibrium + x0 * std::exp(-zeta * omega * t) *
                                          (std::cos(damped * t) + zeta * omega / damped * std::sin(damped * t));
    worst = std::max(worst, std::abs(trajectory.q(0, j) - exact));
  }
  // Phase error ≤ t·ω³h²/12 = 1·20³·1e-8/12 ≈ 6.7e-6 rad, times the amplitude 0.3.
  EXPECT_LT(worst, 0.3 * 1.0 * std::pow(omega, 3) * step * step / 12.0 * 1.2);
}

// A driven coordinate is exact up to its second derivative, and the joint sensor reads it back;
// the relative angle between the two ends of a two-joint chain about z is the sum of the joint angles.
// A wheel of inertia I about its axle, a rotational damper c between the ground and it: I ω̇ = −c ω.
// The trapezoidal rule's own solution of that linear equation is ω_n = ω₀ ((1 − λh/2)/(1 + λh/2))ⁿ
// with λ = c/I, which the run must reproduce to Newton's tolerance.
TEST(ForceElements, RotationalDamperSlowsAWheelAsTheTrapezoidalRuleSays) {
  const double inertia = 0.4, damping = 0.3, step = 0.01, omega0 = 5.0;
  Model model;
  const FrameIndex wheel = model.addRevolute("axle", Model::ground, kZ);
  model.addBody("wheel", wheel, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, inertia).asDiagonal());
  model.addRotationalDamper("bearing", Model::ground, wheel, damping);
  const Trajectory t = run(model, step, 2.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, omega0));
  const double lambda = damping / inertia, factor = (1.0 - 0.5 * lambda * step) / (1.0 + 0.5 * lambda * step);
  for (Eigen::Index k = 0; k < t.time.size(); ++k)
    ASSERT_NEAR(t.v(0, k), omega0 * std::pow(factor, static_cast<double>(k)), 1e-9) << "t = " << t.time[k];
}

// Between two frames that both turn, a rotational damper acts on their relative rate alone, with
// equal and opposite torques: across a revolute about a unit axis it is that joint's damper. Two
// wheels on coaxial axles, the second on the first, under gravity across the axles: the runs agree
// to round-off.
TEST(ForceElements, RotationalDamperAcrossARevoluteIsItsJointDamper) {
  const auto trajectory = [](bool rotational) {
    Model model;
    model.setGravity({0.0, -9.81, 0.0});
    const FrameIndex first = model.addRevolute("first", Model::ground, kZ);
    model.addBody("first_wheel", first, 2.0, {0.3, 0.0, 0.0}, Eigen::Vector3d(0.1, 0.1, 0.2).asDiagonal());
    const FrameIndex second = model.addRevolute("second", model.addOffset("rim", first, {0.5, 0.0, 0.0}), kZ);
    model.addBody("second_wheel", second, 1.0, {0.2, 0.1, 0.0}, Eigen::Vector3d(0.05, 0.05, 0.08).asDiagonal());
    if (rotational) model.addRotationalDamper("bearing", model.frame("rim"), second, 0.7);
    else model.addJointSpringDamper("bearing", "second", 0.0, 0.7);
    return run(model, 1e-3, 1.0, Eigen::Vector2d(0.2, -0.4), Eigen::Vector2d(1.0, 3.0));
  };
  const Trajectory a = trajectory(true), b = trajectory(false);
  EXPECT_LE((a.q - b.q).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT((a.q.col(a.q.cols() - 1) - a.q.col(0)).cwiseAbs().maxCoeff(), 0.1);
}

TEST(Sensors, JointAndRelativeAngleSensorsReadTheDrivenMotion) {
  const double amplitude = 0.7, frequency = 2.5;
  Model model;
  const FrameIndex shoulder = model.addRevolute("shoulder", Model::ground, kZ);
  model.addBody("arm", shoulder, 1.0, 0.5 * kX, kSmallInertia);
  const FrameIndex tip = model.addOffset("tip", shoulder, kX);
  const FrameIndex elbow = model.addRevolute("elbow", tip, kZ);
  model.addBody("forearm", elbow, 1.0, 0.5 * kX, kSmallInertia);
  model.drive("shoulder", TimeFunction::harmonic(amplitude, frequency));
  model.drive("elbow", TimeFunction::polynomial({0.1, 0.2}));
  model.addSensor("shoulder_angle", JointSensor{0, Derivative::Position});
  model.addSensor("shoulder_rate", JointSensor{0, Derivative::Velocity});
  model.addSensor("shoulder_acceleration", JointSensor{0, Derivative::Acceleration});
  model.addSensor("total_turn", RelativeAngleSensor{Model::ground, elbow, kZ});
  const Trajectory trajectory = run(model, 1e-2, 2.0, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2));
  const Eigen::MatrixXd sensors = sensorHistory(model, trajectory);
  for (Eigen::Index k = 0; k < trajectory.time.size(); ++k) {
    const double t = trajectory.time[k], phase = frequency * t;
    EXPECT_NEAR(sensors(k, 0), amplitude * std::sin(phase), 1e-12);
    EXPECT_NEAR(sensors(k, 1), amplitude * frequency * std::cos(phase), 1e-12);
    EXPECT_NEAR(sensors(k, 2), -amplitude * frequency * frequency * std::sin(phase), 1e-12);
    EXPECT_NEAR(sensors(k, 3), std::remainder(amplitude * std::sin(phase) + 0.1 + 0.2 * t, 2 * M_PI), 1e-12);
  }
}
