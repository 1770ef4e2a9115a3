// Models from MJCF and URDF files (7-io/model_file.hpp), checked against MuJoCo itself: MuJoCo's
// RK4 at two small steps (their difference bounds its own error) simulates the same compiled model
// with the same features off, and mbsopt's trajectory must agree within the error mbsopt's
// extrapolation estimates for itself, hinges and slides by their angles and lengths, ball and free
// joints by the rotation vectors of their turns (MuJoCo's quaternions taken to them). The arm is
// written for the tests in MJCF and in URDF (the two must move alike), the double pendulum on ball
// joints in MJCF; the humanoid is MuJoCo's sample model, which no one here wrote.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/io/scene_lookup.hpp"
#include "tests/gradient_checks.hpp"

namespace mbsopt {
namespace {

const std::string kModels = std::string(MBSOPT_SOURCE_DIR) + "/tests/7-io/models/";
const std::string kHumanoid = "/usr/share/mujoco/model/humanoid/humanoid.xml";  // Debian's libmujoco-samples

LoadedScene loadText(const std::string& text, const std::vector<ParameterOverride>& overrides = {}) {
  return loadScene({kModels + "scene.yaml", text}, overrides);
}

/// Starting rates [rad/s or m/s], by mbsopt's coordinate names: `J.v0` overrides for mbsopt, qvel for
/// MuJoCo (a hinge J's dof; a ball J's dof i for J_x, J_y, J_z, its angular velocity in its body's
/// axes, which at φ = 0 is φ̇; a free J's dof i for J_x, J_y, J_z, its velocity in the ground's
/// axes, and 3 + i for J_rx, J_ry, J_rz, its angular velocity as a ball's).
using Rates = std::vector<std::pair<std::string, double>>;

/// The dof of MuJoCo's model that mbsopt's coordinate `name` starts the rate of.
int dofOf(const mjModel* m, const std::string& name) {
  if (const int joint = mj_name2id(m, mjOBJ_JOINT, name.c_str()); joint >= 0) return m->jnt_dofadr[joint];
  const int component = name.back() - 'x';
  for (const auto& [suffix, type, first] : {std::tuple{2, mjJNT_BALL, 0}, std::tuple{2, mjJNT_FREE, 0}, std::tuple{3, mjJNT_FREE, 3}}) {
    const int joint = mj_name2id(m, mjOBJ_JOINT, name.substr(0, name.size() - static_cast<std::size_t>(suffix)).c_str());
    if (joint >= 0 && m->jnt_type[joint] == type) return m->jnt_dofadr[joint] + first + component;
  }
  throw std::runtime_error("no joint of MuJoCo's model for " + name);
}

/// MuJoCo's own run of `path` by RK4 at `step`, the features mbsopt leaves out switched off (flags):
/// the joint positions qpos at every `every` [s] to `end_time` (a column
/// each), and the reference qpos0.
struct MujocoRun {
  Eigen::MatrixXd qpos;
  Eigen::VectorXd qpos0;
};
MujocoRun mujocoRun(const std::string& path, double end_time, double every, double step, int disable_flags,
                    const Rates& rates) {
  std::array<char, 1000> error{};
  const std::unique_ptr<mjModel, decltype(&mj_deleteModel)> m(mj_loadXML(path.c_str(), nullptr, error.data(), 1000),
                                                              &mj_deleteModel);
  if (!m) throw std::runtime_error(error.data());
  m->opt.integrator = mjINT_RK4;
  m->opt.timestep = step;
  m->opt.disableflags |= disable_flags;
  const std::unique_ptr<mjData, decltype(&mj_deleteData)> d(mj_makeData(m.get()), &mj_deleteData);
  for (const auto& [coordinate, rate] : rates) d->qvel[dofOf(m.get(), coordinate)] = rate;
  const long instants = std::lround(end_time / every), steps_between = std::lround(every / step);
  MujocoRun run{Eigen::MatrixXd(m->nq, instants), Eigen::Map<const Eigen::VectorXd>(m->qpos0, m->nq)};
  for (long i = 0; i < instants; ++i) {
    for (long k = 0; k < steps_between; ++k) mj_step(m.get(), d.get());
    run.qpos.col(i) = Eigen::Map<const Eigen::VectorXd>(d->qpos, m->nq);
  }
  return run;
}

/// What of MuJoCo's qpos mbsopt's coordinates hold, each by name: a hinge or slide angle (from
/// qpos0), a free joint's position (the ground's axes), or a component of the rotation vector of a
/// ball's or a free joint's turn from its start quaternion (qpos0), log(q0⁻¹ q).
struct Comparable {
  enum class Kind { FromReference, Absolute, Rotation };
  struct Entry {
    int coordinate;
    int qpos;  ///< the position, or the first of the quaternion (w, x, y, z)
    Kind kind;
    int component;  ///< of the rotation vector
  };
  std::vector<Entry> entries;
};
Comparable comparable(const Model& model, const std::string& path) {
  std::array<char, 1000> error{};
  const std::unique_ptr<mjModel, decltype(&mj_deleteModel)> m(mj_loadXML(path.c_str(), nullptr, error.data(), 1000),
                                                              &mj_deleteModel);
  Comparable out;
  const auto index = [&](const std::string& name) {
    for (int i = 0; i < model.coordinateCount(); ++i)
      if (model.coordinates()[static_cast<std::size_t>(i)].name == name) return i;
    ADD_FAILURE() << "no coordinate " << name;
    return 0;
  };
  using Kind = Comparable::Kind;
  for (int j = 0; j < m->njnt; ++j) {
    const std::string name = mj_id2name(m.get(), mjOBJ_JOINT, j);
    const int a = m->jnt_qposadr[j];
    const int type = m->jnt_type[j];
    if (type == mjJNT_HINGE || type == mjJNT_SLIDE) out.entries.push_back({index(name), a, Kind::FromReference, 0});
    for (int i = 0; i < 3 && type == mjJNT_FREE; ++i)
      out.entries.push_back({index(name + "_" + "xyz"[i]), a + i, Kind::Absolute, 0});
    for (int i = 0; i < 3 && type == mjJNT_FREE; ++i)
      out.entries.push_back({index(name + "_r" + "xyz"[i]), a + 3, Kind::Rotation, i});
    for (int i = 0; i < 3 && type == mjJNT_BALL; ++i)
      out.entries.push_back({index(name + "_" + "xyz"[i]), a, Kind::Rotation, i});
  }
  return out;
}

/// The value of `entry` in MuJoCo's positions qpos, as mbsopt's coordinate holds it.
double inCoordinates(const Comparable::Entry& entry, const Eigen::VectorXd& qpos, const Eigen::VectorXd& qpos0) {
  switch (entry.kind) {
    case Comparable::Kind::FromReference: return qpos[entry.qpos] - qpos0[entry.qpos];
    case Comparable::Kind::Absolute: return qpos[entry.qpos];
    case Comparable::Kind::Rotation: break;
  }
  const auto quaternion = [](const Eigen::VectorXd& x, int i) { return Eigen::Quaterniond(x[i], x[i + 1], x[i + 2], x[i + 3]); };
  const Eigen::AngleAxisd turn(quaternion(qpos0, entry.qpos).conjugate() * quaternion(qpos, entry.qpos));
  return turn.angle() * turn.axis()[entry.component];
}

/// Runs the scene with the extrapolation's error estimate and MuJoCo's RK4 at `step` and `step`/2 on
/// the same model file; every 0.1 s to the end time, each comparable coordinate must agree within
/// mbsopt's estimate and MuJoCo's own error (the RK4 difference bounds the coarser run's error; the
/// finer is taken), each doubled for the next-order terms an asymptotic estimate leaves out.
void expectMujocoAgrees(const std::string& scene_text, const std::string& path, double step, int disable_flags,
                        const Rates& rates = {}) {
  std::vector<ParameterOverride> overrides;
  for (const auto& [joint, rate] : rates) overrides.emplace_back(joint + ".v0", rate);
  const LoadedScene loaded = loadText(scene_text, overrides);
  const Scene& scene = loaded.scene;
  const Integration run = integrate(scene.model, scene.settings, scene.q0, scene.v0, sceneIntegration(scene));
  ASSERT_TRUE(run.estimated);
  const Trajectory& trajectory = run.run.trajectory;
  constexpr double kEvery = 0.1;
  const MujocoRun coarse = mujocoRun(path, scene.settings.end_time, kEvery, step, disable_flags, rates);
  const MujocoRun fine = mujocoRun(path, scene.settings.end_time, kEvery, step / 2, disable_flags, rates);
  const Comparable c = comparable(scene.model, path);
  ASSERT_FALSE(c.entries.empty());
  double moved = 0.0;
  for (Eigen::Index instant = 0; instant < fine.qpos.cols(); ++instant) {
    const double t = kEvery * static_cast<double>(instant + 1);
    Eigen::Index k = 0;  // mbsopt's point at t: its macro steps divide 0.1 s
    while (k + 1 < trajectory.q.cols() && trajectory.time[static_cast<std::size_t>(k)] < t - 1e-9) ++k;
    ASSERT_NEAR(trajectory.time[static_cast<std::size_t>(k)], t, 1e-12);
    for (const Comparable::Entry& entry : c.entries) {
      const int q = entry.coordinate;
      const double reference = inCoordinates(entry, fine.qpos.col(instant), fine.qpos0);
      const double mujoco_error = std::abs(inCoordinates(entry, coarse.qpos.col(instant), fine.qpos0) - reference);
      const double estimate = std::abs(run.run.q_error(q, k));
      EXPECT_LE(std::abs(trajectory.q(q, k) - reference), 2.0 * (estimate + mujoco_error) + 1e-12)
          << scene.model.coordinates()[static_cast<std::size_t>(q)].name << " at t = " << t << " s: mbsopt "
          << trajectory.q(q, k) << ", MuJoCo " << reference << ", mbsopt's estimate " << estimate << ", MuJoCo's "
          << mujoco_error;
      if (entry.kind != Comparable::Kind::Absolute) moved = std::max(moved, std::abs(reference - scene.q0[q]));
    }
  }
  EXPECT_GT(moved, 0.1);  // the joints move: the comparison is of a motion, not of a rest [rad or m]
}

TEST(ModelFile, AnMjcfArmMovesAsMuJoCoMovesIt) {
  expectMujocoAgrees(
      "settings: {end_time: 1.0, step: 2.0e-3, integrator: extrapolation}\n"
      "model: {file: arm.xml, ignore: [limits]}\n",
      kModels + "arm.xml", 1e-4, mjDSBL_LIMIT);
}

TEST(ModelFile, TheHumanoidOfMuJoCosSamplesMovesAsMuJoCoMovesIt) {
  // A free root and 21 hinges, several to a body about anchors off the body's origin, springs and
  // dampers and a rotor inertia (armature) on every hinge; contacts, limits and actuators off in
  // both. Falling freely from rest it would not move inside (every joint at its spring's rest):
  // limbs and waist are thrown.
  expectMujocoAgrees(
      "settings: {end_time: 1.0, step: 2.0e-3, integrator: extrapolation}\n"
      "model: {file: " + kHumanoid + ", ignore: [contacts, limits, actuators]}\n",
      kHumanoid, 1e-4, mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_ACTUATION,
      {{"abdomen_z", 2.0}, {"right_hip_y", -4.0}, {"left_knee", 3.0}, {"right_shoulder1", 5.0}, {"left_elbow", -6.0}});
}

TEST(ModelFile, BallAndFreeJointsWithSpringsAndDampersMoveAsMuJoCoMovesThem) {
  // The balls' and the free body's rotation vectors against MuJoCo's quaternions, all thrown about
  // three axes; springs and dampers on the wrist and on the free body, a damper on the shoulder.
  expectMujocoAgrees(
      "settings: {end_time: 1.0, step: 2.0e-3, integrator: extrapolation}\n"
      "model: {file: ball_pendulum.xml}\n",
      kModels + "ball_pendulum.xml", 1e-4, 0,
      {{"shoulder_x", 1.5}, {"shoulder_y", -1.0}, {"shoulder_z", 2.0}, {"wrist_x", -2.5}, {"wrist_y", 3.0}, {"wrist_z", 1.0},
       {"flyer_x", 0.5}, {"flyer_z", 2.0}, {"flyer_rx", 2.0}, {"flyer_ry", -1.5}, {"flyer_rz", 3.0}});
}

TEST(ModelFile, TheUrdfArmMovesAsItsMjcfTwin) {
  const std::string settings = "settings: {end_time: 1.0, step: 1.0e-3}\n";
  const LoadedScene mjcf = loadText(settings + "model: {file: arm.xml, ignore: [limits]}\n");
  const LoadedScene urdf = loadText(settings + "model: {file: arm.urdf, ignore: [limits]}\n");
  ASSERT_EQ(mjcf.scene.model.coordinateCount(), urdf.scene.model.coordinateCount());
  const auto simulate = [](const Scene& s) { return NewmarkIntegrator(s.model, s.settings).simulate(s.q0, s.v0); };
  const Trajectory a = simulate(mjcf.scene), b = simulate(urdf.scene);
  // The same mechanism, its inertias written in other principal axes: round-off apart.
  EXPECT_LE((a.q - b.q).cwiseAbs().maxCoeff(), 1e-9 * a.q.cwiseAbs().maxCoeff());
  EXPECT_GT(a.q.cwiseAbs().maxCoeff(), 0.1);
}

// With its dampers off nothing takes work out of the arm: the trapezoidal rule keeps its energy to
// O(h²), so halving the step divides the largest departure from the start's energy by 4 (3 to 5
// for the next-order terms), and the departure is small against the energy exchanged.
TEST(ModelFile, TheUndampedArmKeepsItsEnergyToTheIntegratorsOrder) {
  const std::string text =
      "settings: {end_time: 1.0}\n"
      "model: {file: arm.xml, ignore: [limits]}\n"
      "sensors:\n"
      "  - {name: energy, type: energy}\n"
      "  - {name: kinetic, type: energy, part: kinetic}\n";
  const auto departure = [&](double step, double& exchanged) {
    const LoadedScene loaded = loadText(text, {{"settings.step", step}, {"yaw_spring.c", 0.0}, {"elbow_spring.c", 0.0},
                                               {"extension_spring.c", 0.0}});
    const Scene& s = loaded.scene;
    const Trajectory run = NewmarkIntegrator(s.model, s.settings).simulate(s.q0, s.v0);
    exchanged = run.sensors.col(1).maxCoeff();
    return (run.sensors.col(0).array() - run.sensors(0, 0)).abs().maxCoeff();
  };
  double exchanged = 0.0;
  const double coarse = departure(1e-3, exchanged), fine = departure(5e-4, exchanged);
  EXPECT_GT(coarse / fine, 3.0);
  EXPECT_LT(coarse / fine, 5.0);
  EXPECT_LT(fine, 1e-3 * exchanged) << "energy exchanged " << exchanged << " J";
}

/// The 1-based line of `text` in the file at `path` (an independent search of the file).
int lineHolding(const std::string& path, const std::string& text) {
  std::ifstream in(path);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
    if (line.find(text) != std::string::npos) return number;
  return 0;
}

TEST(ModelFile, AFeatureMbsoptDoesNotModelIsRefusedAtItsLine) {
  const auto refusal = [](const std::string& ignore) {
    try {
      loadText("model: {file: " + kHumanoid + ", ignore: [" + ignore + "]}\n");
    } catch (const SceneError& e) {
      return e;
    }
    ADD_FAILURE() << "loaded with ignore: [" << ignore << "]";
    return SceneError("", 0, 0, "");
  };
  const SceneError contacts = refusal("");
  EXPECT_EQ(contacts.path(), kHumanoid);
  EXPECT_EQ(contacts.line(), lineHolding(kHumanoid, "<geom name=\"floor\""));
  EXPECT_NE(contacts.reason().find("contacts"), std::string::npos) << contacts.reason();
  const SceneError limits = refusal("contacts");
  EXPECT_EQ(limits.line(), lineHolding(kHumanoid, "<joint name=\"abdomen_z\""));
  EXPECT_NE(limits.reason().find("limits"), std::string::npos) << limits.reason();
  const SceneError actuators = refusal("contacts, limits");
  EXPECT_EQ(actuators.line(), lineHolding(kHumanoid, "<motor name=\"abdomen_y\""));
  // An unknown feature is the scene's error, at its `ignore`.
  const SceneError unknown = refusal("contact");
  EXPECT_EQ(unknown.path(), kModels + "scene.yaml");
  EXPECT_EQ(unknown.line(), 1);
}

TEST(ModelFile, WhatIsLeftOutIsNamed) {
  const LoadedScene humanoid = loadText("model: {file: " + kHumanoid + ", ignore: [contacts, limits, actuators]}\n");
  ASSERT_EQ(humanoid.left_out.size(), 3u);
  EXPECT_TRUE(humanoid.left_out[0].starts_with("contacts"));
  EXPECT_EQ(humanoid.scene.model.coordinateCount(), 27);  // 6 of the free root and 21 hinges
}

// The file's own switches hold: without gravity and passive forces the arm at rest stays exactly at
// rest (nothing acts on it), and its dampers are not in the model.
TEST(ModelFile, TheFilesGravityAndPassiveSwitchesHold) {
  std::ifstream in(kModels + "arm.xml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string option = "<option gravity=\"0 0 -9.81\"/>";
  ASSERT_NE(text.find(option), std::string::npos);
  text.replace(text.find(option), option.size(),
               "<option gravity=\"0 0 -9.81\"><flag gravity=\"disable\" passive=\"disable\"/></option>");
  const std::string path = testing::TempDir() + "arm_switched_off.xml";
  std::ofstream(path) << text;
  const LoadedScene loaded = loadScene(resolveScene(path), {ParameterOverride::ofWord("model.ignore", "limits")});
  const Scene& s = loaded.scene;
  EXPECT_TRUE(s.model.gravity().isZero(0.0));
  const std::vector<std::string>& names = s.model.parameterNames();
  EXPECT_EQ(std::count_if(names.begin(), names.end(),
                          [](const std::string& n) { return n.find("_spring.") != std::string::npos; }),
            0);
  const Trajectory run = NewmarkIntegrator(s.model, s.settings).simulate(s.q0, s.v0);
  EXPECT_EQ(run.q.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ModelFile, MuJoCosCompilerErrorsKeepTheirLine) {
  const std::string path = testing::TempDir() + "bad.xml";
  std::ofstream(path) << "<mujoco>\n  <worldbody>\n    <body>\n      <joint type=\"hinge\" range=\"0 1\"/>\n"
                         "    </body>\n  </worldbody>\n</mujoco>\n";
  try {
    loadScene(resolveScene(path));
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_EQ(e.line(), 4) << e.what();
  }
}

// A design problem on a model no one here wrote (problems/models/humanoid_arm.yaml: an elbow's
// damping and a lower arm's mass, by the file's names): the adjoint and the direct method are two
// derivations of one recursion (equal to 1e-12), central differences at their best step agree to
// the 1e-6 their truncation and the Newton tolerance leave (test_problem_suite.cpp).
TEST(ModelFile, ADesignProblemOnTheHumanoidHasExactGradients) {
  const DesignProblem problem =
      loadDesignProblem(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/models/humanoid_arm.yaml"));
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = test::expectAdjointEqualsDirect(problem, functionals, x);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

// The same on ball and free joints: the balls' dampers, a ball's spring and a body's mass as the
// variables, the lower rod's swing (a component of its ball's rotation vector) as the cost, the
// free body's turn as a constraint.
TEST(ModelFile, ADesignProblemOnBallJointsHasExactGradients) {
  const std::string text = R"(settings: {end_time: 1.0, step: 2.0e-3}
model:
  file: ball_pendulum.xml
  v0: {shoulder_x: 1.5, shoulder_z: 2.0, wrist_y: 3.0, flyer_rx: 2.0, flyer_rz: 3.0}
sensors:
  - {name: swing, type: joint, joint: wrist_y, quantity: position}
  - {name: turn, type: joint, joint: flyer_rz, quantity: position}
design:
  variables:
    - {parameter: shoulder_damper.c, lower: 0.0, upper: 1.0, scale: 0.1}
    - {parameter: wrist_damper.c, lower: 0.0, upper: 1.0, scale: 0.1}
    - {parameter: wrist_y_spring.k, lower: 0.5, upper: 5.0, scale: 1.0}
    - {parameter: lower.mass, lower: 0.3, upper: 2.0, scale: 1.0}
  cost: {sensor: swing, of: rms}
  artificial: {initial: 2.0, lower: 0, upper: 5, scale: 0.1}
  constraints:
    - {sensor: turn, of: max_abs, bound: 2.0}
)";
  const DesignProblem problem = loadDesignProblem(SceneSource{kModels + "scene.yaml", text});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = test::expectAdjointEqualsDirect(problem, functionals, x);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

TEST(ModelFile, StartsAndOverridesAddressTheFilesOwnNames) {
  const std::string text = "model: {file: arm.xml, ignore: [limits], q0: {elbow: 0.3}, v0: {yaw: 1.5}}\n";
  const LoadedScene loaded = loadText(text, {{"lower.mass", 1.25}, {"shoulder.v0", -2.0}, {"yaw_spring.c", 0.0}});
  const Model& model = loaded.scene.model;
  const auto coordinate = [&](const std::string& name) {
    for (int i = 0; i < model.coordinateCount(); ++i)
      if (model.coordinates()[static_cast<std::size_t>(i)].name == name) return i;
    return -1;
  };
  EXPECT_EQ(loaded.scene.q0[coordinate("elbow")], 0.3);
  EXPECT_EQ(loaded.scene.v0[coordinate("yaw")], 1.5);
  EXPECT_EQ(loaded.scene.v0[coordinate("shoulder")], -2.0);
  EXPECT_EQ(model.parameter("lower.mass"), 1.25);
  EXPECT_EQ(model.parameter("yaw_spring.c"), 0.0);
  EXPECT_EQ(model.parameter("base_placement.translation.z"), 1.0);  // the body's pos in its parent
  try {
    loadText("model: {file: arm.xml, ignore: [limits], v0: {elbw: 1}}\n");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(e.reason().find("did you mean 'elbow'"), std::string::npos) << e.reason();
  }
  EXPECT_THROW(loadText(text, {{"lower.mas", 1.0}}), SceneError);
}

}  // namespace
}  // namespace mbsopt
