// The rotation-vector chart of a ball joint (3-algorithms/ball_chart.hpp) and its kinematics:
// - the chart's coefficients equal their closed forms evaluated in long double (where those lose
//   fewer than 1e-12 to cancellation) on both sides of the switch to the power series at θ = 1, and
//   their limits at φ = 0;
// - the exit frame's rotation is exp([φ]×) (Eigen's angle-axis rotation, an independent formula);
// - the angular velocity and acceleration the recursion gives a ball's exit frame, and the velocity
//   and acceleration of a point beyond it, are the time derivatives of the frame's rotation and of the
//   point's position along the path q(t) = q + q̇ t + q̈ t²/2, by central differences with one
//   Richardson step (error O(h⁴) ≈ 1e-12 at h = 1e-3, round-off ε/h² ≈ 2e-10: tolerance 1e-7), at
//   φ = 0, in the series' range and beyond a half turn, behind a moving revolute (so the entry frame
//   turns too);
// - nothing attaches to the frames inside a ball joint.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "mbsopt/algorithms/ball_chart.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {
namespace {

TEST(BallChart, CoefficientsEqualTheirClosedFormsOnBothSidesOfTheSeries) {
  const BallChartCoefficients<double> zero = ballChartCoefficients(0.0);
  EXPECT_EQ(zero.sinc, 1.0);
  EXPECT_EQ(zero.alpha, 0.5);
  EXPECT_DOUBLE_EQ(zero.beta, 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(zero.alpha_rate, -1.0 / 12.0);
  EXPECT_DOUBLE_EQ(zero.beta_rate, -1.0 / 60.0);
  for (const long double theta : {0.3L, 0.7L, 0.999L, 1.001L, 2.0L, 4.0L, 5.5L}) {
    const long double s = std::sin(theta), c = std::cos(theta), t2 = theta * theta;
    const long double expected[] = {s / theta, (1 - c) / t2, (theta - s) / (t2 * theta), (theta * s - 2 * (1 - c)) / (t2 * t2),
                                    (3 * s - theta * c - 2 * theta) / (t2 * t2 * theta)};
    const BallChartCoefficients<double> chart = ballChartCoefficients(static_cast<double>(t2));
    const double actual[] = {chart.sinc, chart.alpha, chart.beta, chart.alpha_rate, chart.beta_rate};
    for (int i = 0; i < 5; ++i)
      EXPECT_NEAR(actual[i], static_cast<double>(expected[i]), 1e-12 * std::abs(static_cast<double>(expected[i])))
          << "coefficient " << i << " at θ = " << static_cast<double>(theta);
  }
}

/// A revolute about an oblique axis behind a turned offset, a ball joint on it, an offset to a point
/// beyond the ball: the frames the recursion moves.
struct BallOnAHinge {
  Model model;
  FrameIndex ball_exit, tip;
  BallOnAHinge() {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const FrameIndex base = model.addOffset("base", Model::ground, {0.1, -0.2, 0.3}, turn);
    const FrameIndex hinge = model.addRevolute("hinge", base, Eigen::Vector3d(0.3, -0.5, 0.8));
    ball_exit = model.addBallJoint({"ball_x", "ball_y", "ball_z"}, model.addOffset("arm", hinge, {0.4, 0.1, -0.2}));
    tip = model.addOffset("tip", ball_exit, {0.5, -0.3, 0.2});
  }
};

Eigen::Vector3d axial(const Eigen::Matrix3d& skew) { return {skew(2, 1), skew(0, 2), skew(1, 0)}; }

class BallKinematics : public ::testing::TestWithParam<Eigen::Vector3d> {};

TEST_P(BallKinematics, RatesAreTheTimeDerivativesOfTheRotationAndThePosition) {
  BallOnAHinge mechanism;
  const Model& model = mechanism.model;
  Workspace<double> ws(model);
  Eigen::VectorXd q(4), v(4), a(4);
  q << 0.4, GetParam();
  v << 1.3, -0.7, 2.1, 0.9;
  a << -2.0, 3.0, 1.5, -4.0;
  const auto at = [&](double t) {
    forwardKinematics(model, ws, Eigen::VectorXd(q + v * t + 0.5 * a * t * t), v, a, KinematicsLevel::Position);
    return std::pair{ws.rotation[static_cast<std::size_t>(mechanism.ball_exit)], ws.position[static_cast<std::size_t>(mechanism.tip)]};
  };
  // Central differences of the first and second derivative at step h, then Richardson's (4 D(h/2) − D(h))/3.
  const auto derivatives = [&](double h) {
    const auto [Rm, pm] = at(-h);
    const auto [R0, p0] = at(0.0);
    const auto [Rp, pp] = at(h);
    const Eigen::Matrix3d R_rate = (Rp - Rm) / (2 * h), R_second = (Rp - 2 * R0 + Rm) / (h * h);
    // ω× = Ṙ Rᵀ and α× = R̈ Rᵀ + Ṙ Ṙᵀ.
    return std::array<Eigen::Vector3d, 4>{axial(R_rate * R0.transpose()),
                                          axial(R_second * R0.transpose() + R_rate * R_rate.transpose()),
                                          (pp - pm) / (2 * h), (pp - 2 * p0 + pm) / (h * h)};
  };
  constexpr double kStep = 1e-3;
  const auto coarse = derivatives(kStep), fine = derivatives(kStep / 2);
  forwardKinematics(model, ws, q, v, a, KinematicsLevel::Acceleration);
  const auto exit = static_cast<std::size_t>(mechanism.ball_exit), tip = static_cast<std::size_t>(mechanism.tip);
  const Eigen::Vector3d recursion[] = {ws.angular_velocity[exit], ws.angular_acceleration[exit], ws.velocity[tip],
                                       ws.acceleration[tip]};
  const char* const names[] = {"ω of the ball's exit", "α of the ball's exit", "v of the tip", "a of the tip"};
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d reference = (4 * fine[i] - coarse[i]) / 3;
    EXPECT_LE((recursion[i] - reference).norm(), 1e-7 * (1 + reference.norm()))
        << names[i] << ": recursion " << recursion[i].transpose() << ", differences " << reference.transpose();
  }
  // And the exit is turned from its entry by exp([φ]×).
  const Eigen::Vector3d phi = GetParam();
  const Eigen::Matrix3d expected =
      ws.rotation[static_cast<std::size_t>(model.frame("arm"))] *
      (phi.norm() > 0 ? Eigen::AngleAxisd(phi.norm(), phi.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity());
  EXPECT_LE((ws.rotation[exit] - expected).cwiseAbs().maxCoeff(), 1e-14);
}

INSTANTIATE_TEST_SUITE_P(AtRestInTheSeriesAndBeyondAHalfTurn, BallKinematics,
                         ::testing::Values(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.3, -0.5, 0.2),
                                           Eigen::Vector3d(2.5, -2.0, 1.5)));

TEST(BallJoint, NothingAttachesInsideIt) {
  BallOnAHinge mechanism;
  Model& model = mechanism.model;
  EXPECT_EQ(model.coordinateCount(), 4);
  EXPECT_FALSE(model.planar());
  for (const char* inside : {"ball_x", "ball_y"}) {
    try {
      model.addBody("bob", model.frame(inside), 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
      ADD_FAILURE() << "a body was attached to " << inside;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("lies inside a ball joint, whose exit frame is 'ball_z'"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_NO_THROW(model.addBody("bob", mechanism.ball_exit, 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()));
}

TEST(BallJoint, IsRefusedBeyondTheEndOfItsChart) {
  BallOnAHinge mechanism;
  Workspace<double> ws(mechanism.model);
  Eigen::VectorXd q(4);
  q << 0.0, 0.0, 0.0, 1.81 * std::numbers::pi;
  EXPECT_THROW(forwardKinematics(mechanism.model, ws, q, q, q, KinematicsLevel::Position), DegenerateElementError);
  q[3] = 1.79 * std::numbers::pi;
  EXPECT_NO_THROW(forwardKinematics(mechanism.model, ws, q, q, q, KinematicsLevel::Position));
}

}  // namespace
}  // namespace mbsopt
