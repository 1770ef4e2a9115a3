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
//   so the run must keep q_y, q̇_x and q_z at their start to Newton's round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

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

}  // namespace
}  // namespace mbsopt
