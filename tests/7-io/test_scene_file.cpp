// The scene-file loader: the shipped tramway.yaml is the C++ tramway scene, `--set` overrides are
// the model's parameters, and the format's features (degrees, offsets with rotations, time
// functions, assembly of the initial state) mean what problems/scenes/README.md says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/io/scene_text.hpp"
#include "mbsopt/design/tramway.hpp"

namespace mbsopt {
namespace {

LoadedScene loadShipped(const std::string& name, const std::vector<ParameterOverride>& overrides = {}) {
  return loadScene(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml"), overrides);
}

LoadedScene loadText(const std::string& text) { return loadScene({"inline.yaml", text}); }

// The file builds the same elements, in the same order, as tramwayScene(): the same coordinates and
// the same arithmetic, so the trajectories agree to round-off over the whole run (1e-12 relative
// leaves room for a different but equally rounded parsing of a constant; any modelling difference,
// e.g. a point 1 mm off, shows at 1e-4).
void expectSameTramway(const std::string& file_name, BogieYawChart chart) {
  const LoadedScene file = loadShipped(file_name);
  EXPECT_TRUE(file.warnings.empty());
  TramwayOptions options;
  options.chart = chart;
  const Scene builtin = tramwayScene(TramwayDesign{}, options);
  ASSERT_EQ(file.scene.model.coordinateCount(), builtin.model.coordinateCount());
  for (int i = 0; i < builtin.model.coordinateCount(); ++i)
    EXPECT_EQ(file.scene.model.coordinates()[i].name, builtin.model.coordinates()[i].name);
  EXPECT_EQ(file.scene.model.drivenCoordinates(), builtin.model.drivenCoordinates());
  EXPECT_EQ(file.scene.model.constraintCount(), builtin.model.constraintCount());
  EXPECT_EQ(file.scene.q0, builtin.q0);
  EXPECT_EQ(file.scene.v0, builtin.v0);
  EXPECT_EQ(file.scene.settings.step, builtin.settings.step);
  EXPECT_EQ(file.scene.settings.end_time, builtin.settings.end_time);
  for (const std::string& name : builtin.model.parameterNames())
    EXPECT_EQ(file.scene.model.parameter(name), builtin.model.parameter(name)) << name;

  const Trajectory a = NewmarkIntegrator(file.scene.model, file.scene.settings).simulate(file.scene.q0, file.scene.v0);
  const Trajectory b = NewmarkIntegrator(builtin.model, builtin.settings).simulate(builtin.q0, builtin.v0);
  ASSERT_EQ(a.q.cols(), b.q.cols());
  EXPECT_LE((a.q - b.q).cwiseAbs().maxCoeff(), 1e-12 * b.q.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd sa = sensorHistory(file.scene.model, a), sb = sensorHistory(builtin.model, b);
  for (Eigen::Index s = 0; s < sb.cols(); ++s)
    EXPECT_LE((sa.col(s) - sb.col(s)).cwiseAbs().maxCoeff(), 1e-12 * sb.col(s).cwiseAbs().maxCoeff())
        << builtin.model.sensors()[static_cast<std::size_t>(s)].name;
}

TEST(TramwaySceneFile, EqualsTheBuiltInScene) { expectSameTramway("tramway", BogieYawChart::Absolute); }

TEST(TramwaySceneFile, TrackChartFileEqualsTheBuiltInTrackChart) {
  expectSameTramway("tramway_track_chart", BogieYawChart::RelativeToTrack);
}

// `--set` on the file and the C++ design argument are the same design; a model parameter the file
// leaves at its default (a centre of mass) is set on the model.
TEST(TramwaySceneFile, OverridesAreTheDesign) {
  const LoadedScene file = loadShipped(
      "tramway", {{"front_secondary.k", 500e3}, {"rear_secondary.c", 30e3}, {"carbody1.com.x", 0.25}});
  Scene builtin = tramwayScene(TramwayDesign{500e3, 246e3, 15e3, 30e3}, TramwayOptions{});
  builtin.model.setParameter("carbody1.com.x", 0.25);
  for (const std::string& name : builtin.model.parameterNames())
    EXPECT_EQ(file.scene.model.parameter(name), builtin.model.parameter(name)) << name;
  EXPECT_THROW(loadShipped("tramway", {{"front_secondary.kk", 1.0}}), SceneError);
  EXPECT_THROW(loadShipped("tramway", {{"carbody1.Izz", -1.0}}), SceneError);
}

// The naming contract of the README: the model's parameter names are the file's dotted names.
TEST(TramwaySceneFile, ModelParameterNamesAreFileNames) {
  const SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml");
  const auto parameters = sceneParameters(source);
  const Model model = loadScene(source).scene.model;
  for (const std::string& name : model.parameterNames()) {
    const auto found = std::find_if(parameters.begin(), parameters.end(), [&](const auto& p) { return p.first == name; });
    ASSERT_NE(found, parameters.end()) << name;
    EXPECT_EQ(found->second, model.parameter(name)) << name;
  }
}

TEST(SceneFile, BuiltInScenesAreTheShippedFiles) {
  for (const std::string& name : builtinSceneNames()) {
    const SceneSource file = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml");
    ASSERT_TRUE(builtinScene(name).has_value());
    EXPECT_EQ(builtinScene(name)->text, file.text) << name;
  }
  EXPECT_GE(builtinSceneNames().size(), 5u);
  EXPECT_FALSE(builtinScene("no_such_scene").has_value());
}

TEST(SceneFile, DegreesAreExact) {
  double value = 0.0;
  std::string why;
  ASSERT_TRUE(parseNumber("90 deg", value, why));
  EXPECT_EQ(value, std::numbers::pi / 2);
  ASSERT_TRUE(parseNumber("-45deg", value, why));
  EXPECT_EQ(value, -std::numbers::pi / 4);
  ASSERT_TRUE(parseNumber("+2.5e3", value, why));
  EXPECT_EQ(value, 2500.0);
  EXPECT_FALSE(parseNumber("1e999", value, why));
  EXPECT_FALSE(parseNumber("nan", value, why));
  EXPECT_FALSE(parseNumber("3 m", value, why));
  EXPECT_FALSE(parseNumber("+-1", value, why));
  EXPECT_FALSE(parseNumber("1e-400", value, why));
  EXPECT_NE(why.find("underflows"), std::string::npos) << why;
  EXPECT_EQ(formatNumber(0.1), "0.1");  // shortest round trip
  EXPECT_EQ(formatNumber(-9.81), "-9.81");
  EXPECT_EQ(quoted("a\nb"), "'a\\x0ab'");  // one line, whatever the user typed
}

// Numbers the file leaves at their defaults are addressable too, and are checked like written ones.
TEST(SceneFile, OverridesReachDefaults) {
  const SceneSource source{"inline.yaml", R"(
elements:
  - {name: hinge, type: revolute, parent: ground, axis: [0, 0, 1]}
bodies:
  - {name: bob, frame: hinge, mass: 1, Ixx: 1, Iyy: 1, Izz: 1}
)"};
  const LoadedScene loaded = loadScene(
      source, {{"settings.beta", 0.3}, {"hinge.q0", 0.5}, {"bob.com.x", 0.25}, {"gravity.y", -9.81}});
  EXPECT_EQ(loaded.scene.settings.beta, 0.3);
  EXPECT_EQ(loaded.scene.q0[0], 0.5);
  EXPECT_EQ(loaded.scene.model.parameter("bob.com.x"), 0.25);
  EXPECT_EQ(loaded.scene.model.gravity().y(), -9.81);
  EXPECT_THROW(loadScene(source, {{"settings.beta", 0.9}}), SceneError);  // outside (0, 1/2]
  EXPECT_THROW(loadScene(source, {{"hinge.stiffness", 1.0}}), SceneError);  // not a key of a revolute joint
  EXPECT_THROW(loadScene(source, {{"nobody.mass", 1.0}}), SceneError);
  const auto parameters = sceneParameters(source);
  for (const char* name : {"settings.gamma", "hinge.q0", "hinge.v0", "bob.com.y", "gravity.z"})
    EXPECT_TRUE(std::any_of(parameters.begin(), parameters.end(), [&](const auto& p) { return p.first == name; }))
        << name;
}

// An alias would give one number two names (and a self-referencing one, an endless tree).
TEST(SceneFile, AliasesAreRefused) {
  EXPECT_THROW(loadText("elements: []\nbodies: []\nsettings: &s {x: *s}\n"), SceneError);
  EXPECT_THROW(loadText("elements:\n  - {name: a, type: revolute, parent: ground, axis: &z [0, 0, 1]}\n"
                        "  - {name: b, type: revolute, parent: a, axis: *z}\nbodies: []\n"),
               SceneError);
}

// An offset turned 90° about z then lifted, a prismatic joint along its x axis driven by
// s(t) = 0.2 + 0.1 t + 0.3 sin(2t + 0.5): the point must move along the world's y axis at height 1,
// exactly as the time function says, its velocity and acceleration too (closed form, so round-off).
TEST(SceneFile, OffsetRotationPrismaticAndTimeFunction) {
  const LoadedScene loaded = loadText(R"(
settings: {step: 0.01, end_time: 1}
elements:
  - {name: post, type: offset, parent: ground, translation: [0, 0, 1], rotation: {axis: [0, 0, 2], angle: 90 deg}}
  - {name: slide, type: prismatic, parent: post, axis: [1, 0, 0],
     motion: {polynomial: [0.2, 0.1], harmonics: [{amplitude: 0.3, angular_frequency: 2, phase: 0.5}]}}
bodies:
  - {name: block, frame: slide, mass: 1, Ixx: 1, Iyy: 1, Izz: 1}
sensors:
  - {name: x, type: point, frame: slide, quantity: position, component: x}
  - {name: y, type: point, frame: slide, quantity: position, component: y}
  - {name: z, type: point, frame: slide, quantity: position, component: z}
  - {name: vy, type: point, frame: slide, quantity: velocity, component: y}
  - {name: ay, type: point, frame: slide, quantity: acceleration, component: y}
)");
  const Scene& scene = loaded.scene;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const Eigen::MatrixXd sensors = sensorHistory(scene.model, trajectory);
  for (Eigen::Index k = 0; k < trajectory.time.size(); ++k) {
    const double t = trajectory.time[k];
    EXPECT_NEAR(sensors(k, 0), 0.0, 1e-15);
    EXPECT_NEAR(sensors(k, 1), 0.2 + 0.1 * t + 0.3 * std::sin(2 * t + 0.5), 1e-14);
    EXPECT_NEAR(sensors(k, 2), 1.0, 1e-15);
    EXPECT_NEAR(sensors(k, 3), 0.1 + 0.6 * std::cos(2 * t + 0.5), 1e-14);
    EXPECT_NEAR(sensors(k, 4), -1.2 * std::sin(2 * t + 0.5), 1e-13);
  }
}

// A parallelogram four-bar (crank and rocker 1 m, ground and coupler 2 m) given a rocker angle 0.1 rad
// off the crank's: the loader moves the state onto the closure (a parallelogram keeps both angles
// equal), says so, and the result closes the loop to round-off.
TEST(SceneFile, InitialStateIsAssembledWithAWarning) {
  const LoadedScene loaded = loadText(R"(
elements:
  - {name: crank, type: revolute, parent: ground, axis: [0, 0, 1], q0: 1.0}
  - {name: crank_end, type: offset, parent: crank, translation: [1, 0, 0]}
  - {name: coupler, type: revolute, parent: crank_end, axis: [0, 0, 1], q0: -1.0}
  - {name: coupler_end, type: offset, parent: coupler, translation: [2, 0, 0]}
  - {name: rocker_base, type: offset, parent: ground, translation: [2, 0, 0]}
  - {name: rocker, type: revolute, parent: rocker_base, axis: [0, 0, 1], q0: 1.1}
  - {name: rocker_end, type: offset, parent: rocker, translation: [1, 0, 0]}
bodies:
  - {name: crank_body, frame: crank, mass: 1, com: [0.5, 0, 0], Ixx: 0.1, Iyy: 0.1, Izz: 0.1}
cuts:
  - {name: pin, type: spherical, frame_a: coupler_end, frame_b: rocker_end}
)");
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("inline.yaml: warning: the initial coordinates do not close the loops"),
            std::string::npos)
      << loaded.warnings[0];
  const Scene& scene = loaded.scene;
  Workspace<double> ws(scene.model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(scene.q0.size());
  forwardKinematics(scene.model, ws, scene.q0, zero, zero, KinematicsLevel::Position);
  Eigen::VectorXd b(scene.model.constraintCount());
  closureEquations(scene.model, ws, Derivative::Position, b);
  EXPECT_LE(b.cwiseAbs().maxCoeff(), 1e-12);
  const double crank = scene.q0[scene.model.coordinate("crank")];
  const double rocker = scene.q0[scene.model.coordinate("rocker")];
  EXPECT_NEAR(crank, rocker, 1e-12);                   // a parallelogram
  EXPECT_NEAR(scene.q0[scene.model.coordinate("coupler")], -crank, 1e-12);
}

TEST(SceneFile, ErrorsNameTheLine) {
  try {
    loadText("elements:\n  - {name: a, type: revolute, parent: ground, axis: [0, 0, 1]}\nbodies:\n"
             "  - {name: b, frame: a, mass: 1, Ixx: 1, Iyy: 1, Izz: 1, Ixx: 2}\n");
    FAIL() << "a duplicate key was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_NE(e.reason().find("duplicate key 'Ixx'"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("inline.yaml:4:", 0), 0u) << e.what();
  }
}

// ---- the size limits of problems/scenes/README.md, "Limits" ----

/// A pendulum whose `bodies:` section lists `count` point masses on the one joint (from line 5).
std::string pendulumWithBodies(std::size_t count) {
  std::string text =
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: arm, type: revolute, parent: ground, axis: [0, 1, 0], q0: 30 deg}\n"
      "bodies:\n";
  for (std::size_t i = 0; i < count; ++i)
    text += "  - {name: b" + std::to_string(i) + ", frame: arm, mass: 1.0, com: [0, 0, -1], Ixx: 0, Iyy: 0, Izz: 0}\n";
  return text;
}

// Two-sided: a section of exactly the limit loads (and is the same pendulum), one more entry is
// refused at that entry's line.
TEST(SceneLimits, SectionEntriesLimitIsExact) {
  const std::size_t limit = kSceneLimits.entries_per_section;
  EXPECT_EQ(loadText(pendulumWithBodies(limit)).scene.model.coordinateCount(), 1);
  try {
    loadText(pendulumWithBodies(limit + 1));
    FAIL() << "a section of " << limit + 1 << " entries was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 5 + static_cast<int>(limit)) << e.what();
    EXPECT_NE(std::string(e.what()).find("more than " + std::to_string(limit) + " entries"), std::string::npos)
        << e.what();
  }
}

// A chain of one joint more than the limit is refused at that joint, before any dynamics is built.
TEST(SceneLimits, CoordinateLimitNamesTheJointBeyondIt) {
  std::string text = "elements:\n";  // line 1; joint j_k on line k + 1
  std::string parent = "ground";
  for (int k = 1; k <= kSceneLimits.coordinates + 1; ++k) {
    text += "  - {name: j" + std::to_string(k) + ", type: revolute, parent: " + parent + ", axis: [0, 1, 0]}\n";
    parent = "j" + std::to_string(k);
  }
  text += "bodies:\n  - {name: b, frame: j1, mass: 1.0, com: [0, 0, -1], Ixx: 0.01, Iyy: 0.01, Izz: 0.01}\n";
  try {
    loadText(text);
    FAIL() << "a model of " << kSceneLimits.coordinates + 1 << " coordinates was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), kSceneLimits.coordinates + 2) << e.what();
    EXPECT_NE(std::string(e.what()).find("j" + std::to_string(kSceneLimits.coordinates + 1)), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mbsopt
