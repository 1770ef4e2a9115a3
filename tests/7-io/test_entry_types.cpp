// The registries of the scene files' entry types (7-io/entry_type.hpp: elements, cuts, forces,
// sensors) and the element type added through one in one file, the spherical joint
// (7-io/elements/spherical.cpp):
// - every registered type has a unique name and a description; in every section an unknown type is
//   refused at its line with every registered name, and a key its type does not take is refused;
// - a spherical joint is exactly the chain it stands for, three revolutes about x, y', z'' and a
//   frame: the same trajectory to the bit as that chain written out;
// - a rigid body on a spherical joint in steady conical rotation, ω = Ω e about the vertical e with
//   its symmetry axis at θ from it, is a motion of the equations exactly when the gravity moment
//   balances the gyroscopic one, m g l sin θ = Ω² (I₂ − I₁) sin θ cos θ (I₁ about the symmetry
//   axis, I₂ across it, both about the pivot). In the Cardan angles that motion is q_x = Ω t,
//   q_y = θ, q_z = 0: constant rates and no acceleration, which the Newmark rule integrates exactly,
//   so the run must keep q_y, q̇_x and q_z at their start to Newton's round-off;
// - a ball joint (7-io/elements/ball.cpp), a rotation vector φ, takes the same conical rotation,
//   R(t) = R_x(Ω t) R_y(θ): there φ(t) is not linear in t, the rule's error is of second order, and
//   the orientation's error must fall by 4 (within [3.5, 4.5]) as the step halves, past |φ| = π;
// - a free asymmetric body on a ball joint about its centre, spinning about its major axis and
//   precessing, turns through a quarter turn about its parent's y axis (where Cardan angles lock)
//   and keeps its angular momentum in ground axes to the rule's second order: its drift falls by 4
//   (within [3.5, 4.5]) as the step halves.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/io/element_type.hpp"
#include "mbsopt/io/entry_type.hpp"
#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {
namespace {

LoadedScene sceneOf(const std::string& text) { return loadScene(SceneSource{"elements.yaml", text}); }

Trajectory simulated(const Scene& scene) { return NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0); }

template <class Entry>
void expectUniqueNamesAndDescriptions(const std::vector<EntryType<Entry>>& registry, const std::string& what) {
  std::set<std::string> names;
  for (const EntryType<Entry>& type : registry) {
    EXPECT_TRUE(names.insert(type.name).second) << what << " " << type.name;
    EXPECT_FALSE(type.description.empty()) << what << " " << type.name;
    EXPECT_EQ(&entryType(registry, type.name, what), &type);
  }
  EXPECT_THROW(entryType(registry, "ball_and_socket", what), std::invalid_argument);
}

TEST(EntryTypes, EveryRegisteredTypeHasAUniqueNameAndADescription) {
  expectUniqueNamesAndDescriptions(elementTypes(), "element");
  expectUniqueNamesAndDescriptions(cutTypes(), "cut");
  expectUniqueNamesAndDescriptions(forceTypes(), "force");
  expectUniqueNamesAndDescriptions(sensorTypes(), "sensor");
}

// A pendulum whose section `section` ends with `entry` (at line 6 of the file).
std::string pendulumWith(const std::string& section, const std::string& entry) {
  std::string text = "elements:\n  - {name: arm, type: revolute, parent: ground, axis: [0, 0, 1]}\n"
                     "bodies:\n  - {name: bob, frame: arm, mass: 1, com: [1, 0, 0], Ixx: 1, Iyy: 1, Izz: 1}\n";
  if (section == "elements") return "bodies:\n  - {name: bob, frame: arm, mass: 1, Ixx: 1, Iyy: 1, Izz: 1}\n"
                                    "elements:\n  - {name: arm, type: revolute, parent: ground, axis: [0, 1, 0]}\n"
                                    "  - {name: bob_mount, type: offset, parent: arm}\n" + entry;
  return text + section + ":\n" + entry;
}

void expectRefusedAtLineSix(const std::string& text, const std::vector<std::string>& words) {
  try {
    sceneOf(text);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 6) << e.what();
    for (const std::string& word : words) EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(EntryTypes, AnUnknownTypeIsRefusedAtItsLineWithEveryRegisteredName) {
  const std::pair<std::string, std::vector<std::string>> sections[] = {
      {"elements", entryTypeNames(elementTypes())},
      {"cuts", entryTypeNames(cutTypes())},
      {"forces", entryTypeNames(forceTypes())},
      {"sensors", entryTypeNames(sensorTypes())},
  };
  for (const auto& [section, names] : sections) {
    SCOPED_TRACE(section);
    const std::string parent = section == "elements" ? ", parent: ground" : "";
    expectRefusedAtLineSix(pendulumWith(section, "  - {name: odd, type: hinge" + parent + "}\n"), names);
  }
}

TEST(EntryTypes, AKeyItsTypeDoesNotTakeIsRefusedAtItsLine) {
  expectRefusedAtLineSix(pendulumWith("forces", "  - {name: spring, type: joint_spring_damper, joint: arm, k: 1, "
                                                "stiffness: 2}\n"),
                         {"stiffness"});
  expectRefusedAtLineSix(pendulumWith("sensors", "  - {name: angle, type: joint, joint: arm, quantity: position, "
                                                 "axis: [0, 0, 1]}\n"),
                         {"axis"});
  expectRefusedAtLineSix(pendulumWith("cuts", "  - {name: pin, type: spherical, frame_a: arm, frame_b: ground, "
                                              "axis_in_a: [0, 0, 1]}\n"),
                         {"axis_in_a"});
}

constexpr const char* kBody = R"(
bodies:
  - {name: top, frame: ball, mass: 1.0, com: [-1, 0, 0], Ixx: 0.01, Iyy: 0.02, Izz: 0.02}
)";

TEST(SphericalJoint, IsTheChainOfThreeRevolutesItStandsFor) {
  const std::string settings = "gravity: [0, 0, -9.81]\nsettings: {step: 1.0e-3, end_time: 0.5}\n";
  const LoadedScene ball = sceneOf(settings + R"(elements:
  - {name: ball, type: spherical, parent: ground, q0: [0.3, -0.4, 0.5], v0: [1.0, 0.5, -2.0]}
)" + kBody);
  const LoadedScene chain = sceneOf(settings + R"(elements:
  - {name: ball_x, type: revolute, parent: ground, axis: [1, 0, 0], q0: 0.3, v0: 1.0}
  - {name: ball_y, type: revolute, parent: ball_x, axis: [0, 1, 0], q0: -0.4, v0: 0.5}
  - {name: ball_z, type: revolute, parent: ball_y, axis: [0, 0, 1], q0: 0.5, v0: -2.0}
  - {name: ball, type: offset, parent: ball_z}
)" + kBody);
  ASSERT_EQ(ball.scene.model.coordinateCount(), 3);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(ball.scene.model.coordinates()[static_cast<std::size_t>(i)].name, chain.scene.model.coordinates()[static_cast<std::size_t>(i)].name);
  const Trajectory a = simulated(ball.scene), b = simulated(chain.scene);
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.v, b.v);
}

TEST(SphericalJoint, KeepsASteadyConicalRotationOfARigidBody) {
  // Gravity along −x, the vertical the first Cardan axis; the body's symmetry axis is its x axis,
  // its centre l = 1 m from the pivot: I₁ = 0.01, I₂ = 0.02 + m l² (kBody).
  const double g = 9.81, m = 1.0, l = 1.0, i1 = 0.01, i2 = 0.02 + m * l * l, theta = std::numbers::pi / 6.0;
  const double omega = std::sqrt(m * g * l / ((i2 - i1) * std::cos(theta)));
  char start[160];
  std::snprintf(start, sizeof start, "  - {name: ball, type: spherical, parent: ground, q0: [0, %.17g, 0], v0: [%.17g, 0, 0]}\n",
                theta, omega);
  const LoadedScene loaded =
      sceneOf(std::string("gravity: [-9.81, 0, 0]\nsettings: {step: 1.0e-3, end_time: 2}\nelements:\n") + start + kBody);
  const Trajectory t = simulated(loaded.scene);
  // Newton stops within 1e-10 of q̈ = 0 (NewmarkSettings::newton_tolerance), which over 2000 steps
  // of 1 ms moves q by at most ½·1e-10·T² = 2e-10; round-off adds less.
  for (Eigen::Index k = 0; k < t.time.size(); ++k) {
    ASSERT_NEAR(t.q(0, k), omega * t.time[k], 1e-8 * (1.0 + omega * t.time[k])) << "t = " << t.time[k];
    ASSERT_NEAR(t.q(1, k), theta, 1e-8) << "t = " << t.time[k];
    ASSERT_NEAR(t.q(2, k), 0.0, 1e-8) << "t = " << t.time[k];
  }
}

/// exp([φ]×), by Eigen's angle-axis rotation.
Eigen::Matrix3d rotationOf(const Eigen::Vector3d& phi) {
  return phi.norm() > 0 ? Eigen::AngleAxisd(phi.norm(), phi.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
}

/// A ball joint's scene at step h, its start a rotation vector and its rate.
LoadedScene ballScene(double h, double end_time, const std::string& gravity, const Eigen::Vector3d& q0,
                      const Eigen::Vector3d& v0, const std::string& body) {
  char text[600];
  std::snprintf(text, sizeof text,
                "gravity: %s\nsettings: {step: %.17g, end_time: %.17g}\nelements:\n"
                "  - {name: ball, type: ball, parent: ground, q0: [%.17g, %.17g, %.17g], v0: [%.17g, %.17g, %.17g]}\n%s",
                gravity.c_str(), h, end_time, q0.x(), q0.y(), q0.z(), v0.x(), v0.y(), v0.z(), body.c_str());
  return sceneOf(text);
}

/// The ratio of the errors at steps h and h/2, and the error at h/2.
void expectSecondOrder(double coarse, double fine, const std::string& what) {
  EXPECT_GT(coarse / fine, 3.5) << what << ": error " << coarse << " at h, " << fine << " at h/2";
  EXPECT_LT(coarse / fine, 4.5) << what << ": error " << coarse << " at h, " << fine << " at h/2";
}

TEST(BallJoint, KeepsASteadyConicalRotationOfARigidBodyToTheRulesOrder) {
  // As the spherical joint's test above; the start φ = θ e_y, φ̇ = J(φ)⁻¹ Ω e_x with the left
  // Jacobian J = 1 + (1 − cos θ)/θ² [φ]× + (θ − sin θ)/θ³ [φ]×².
  const double g = 9.81, m = 1.0, l = 1.0, i1 = 0.01, i2 = 0.02 + m * l * l, theta = std::numbers::pi / 6.0;
  const double omega = std::sqrt(m * g * l / ((i2 - i1) * std::cos(theta)));
  const Eigen::Vector3d phi0(0.0, theta, 0.0);
  Eigen::Matrix3d K;
  K << 0, -phi0.z(), phi0.y(), phi0.z(), 0, -phi0.x(), -phi0.y(), phi0.x(), 0;
  const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() + (1 - std::cos(theta)) / (theta * theta) * K +
                            (theta - std::sin(theta)) / (theta * theta * theta) * K * K;
  const Eigen::Vector3d rate = J.inverse() * Eigen::Vector3d(omega, 0, 0);
  const auto error = [&](double h) {
    const LoadedScene loaded = ballScene(h, 1.0, "[-9.81, 0, 0]", phi0, rate, kBody);
    const Trajectory t = simulated(loaded.scene);
    double worst = 0.0, turn = 0.0;
    for (Eigen::Index k = 0; k < t.time.size(); ++k) {
      const Eigen::Matrix3d exact = Eigen::AngleAxisd(omega * t.time[k], Eigen::Vector3d::UnitX()).toRotationMatrix() *
                                    Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
      worst = std::max(worst, (rotationOf(t.q.col(k).head<3>()) - exact).cwiseAbs().maxCoeff());
      turn = std::max(turn, t.q.col(k).head<3>().norm());
    }
    EXPECT_GT(turn, std::numbers::pi);  // past the half turn where a principal logarithm would jump
    return worst;
  };
  expectSecondOrder(error(2e-3), error(1e-3), "orientation");
}

TEST(BallJoint, KeepsTheAngularMomentumOfAFreeBodyThroughAQuarterTurnToTheRulesOrder) {
  // Principal moments 1, 3, 2 kg m² about the centre: y is the major axis.
  const std::string body = "bodies:\n  - {name: top, frame: ball, mass: 1.0, Ixx: 1, Iyy: 3, Izz: 2}\n";
  const Eigen::Vector3d spin(0.3, 2.5, 0.2);  // φ̇ = ω at φ = 0 (J(0) = 1)
  double largest_turn_about_y = 0.0;
  const auto drift = [&](double h) {
    const LoadedScene loaded = ballScene(h, 1.0, "[0, 0, 0]", Eigen::Vector3d::Zero(), spin, body);
    const Model& model = loaded.scene.model;
    const Trajectory t = simulated(loaded.scene);
    Workspace<double> ws(model);
    const auto frame = static_cast<std::size_t>(model.frame("ball"));
    const Eigen::Matrix3d inertia = Eigen::Vector3d(1, 3, 2).asDiagonal();
    const auto momentum = [&](Eigen::Index k) {  // L = R I Rᵀ ω
      forwardKinematics(model, ws, Eigen::VectorXd(t.q.col(k)), Eigen::VectorXd(t.v.col(k)),
                        Eigen::VectorXd::Zero(3).eval(), KinematicsLevel::Velocity);
      const Eigen::Matrix3d& R = ws.rotation[frame];
      return Eigen::Vector3d(R * inertia * R.transpose() * ws.angular_velocity[frame]);
    };
    const Eigen::Vector3d start = momentum(0);
    double worst = 0.0;
    for (Eigen::Index k = 0; k < t.time.size(); ++k) {
      worst = std::max(worst, (momentum(k) - start).norm());
      const Eigen::Matrix3d& R = ws.rotation[frame];
      largest_turn_about_y = std::max(largest_turn_about_y, std::abs(std::atan2(R(0, 2), R(2, 2))));
    }
    return worst;
  };
  expectSecondOrder(drift(2e-3), drift(1e-3), "angular momentum");
  EXPECT_GT(largest_turn_about_y, std::numbers::pi / 2);
}

}  // namespace
}  // namespace mbsopt
