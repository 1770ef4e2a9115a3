// The mechanical energy (3-algorithms/energy.hpp) and the `energy` sensor: kinetic and gravity parts
// against the independent test helper (tests/mechanical_energy.hpp), spring potentials against
// closed forms, and conservation in undamped runs within the bounds the trapezoidal rule implies.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <utility>

#include "mbsopt/algorithms/energy.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/mechanical_energy.hpp"

namespace mbsopt {
namespace {

LoadedScene loadShipped(const std::string& name) {
  return loadScene(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml"));
}

// The same sums from the same kinematics in another arrangement (ωᵀ R I Rᵀ ω against (Rᵀω)ᵀ I (Rᵀω)):
// equal to round-off, 1e-13 of the energies' scale.
TEST(MechanicalEnergy, KineticAndGravityAgreeWithTheTestHelper) {
  for (const char* name : {"double_pendulum", "four_bar", "slider_crank"}) {
    const Scene scene = loadShipped(name).scene;
    Workspace<double> ws(scene.model);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-2.0, 2.0);
    for (int trial = 0; trial < 5; ++trial) {
      Eigen::VectorXd q(scene.model.coordinateCount()), v(q.size());
      for (Eigen::Index i = 0; i < q.size(); ++i) {
        q[i] = uniform(random);
        v[i] = uniform(random);
      }
      const test::Energy expected = test::mechanicalEnergy(scene.model, ws, q, v);
      const MechanicalEnergy energy = mechanicalEnergy(scene.model, ws, q, v, 0.0);
      const double scale = 1.0 + std::abs(expected.kinetic) + std::abs(expected.potential);
      EXPECT_NEAR(energy.kinetic, expected.kinetic, 1e-13 * scale) << name;
      EXPECT_NEAR(energy.gravity, expected.potential, 1e-13 * scale) << name;
      EXPECT_EQ(energy.springs, 0.0) << name;
    }
  }
}

// One spring of each kind, in a state where its stretch is known by construction.
TEST(MechanicalEnergy, SpringPotentialsAreTheClosedForms) {
  Track track(Eigen::Vector3d::Zero(), 0.3);
  track.arc(10.0, std::numbers::pi / 2);  // ψ(s) = 0.3 + s/10
  Model model;
  const FrameIndex cart = model.addCurveSlider("cart", Model::ground, model.addTrack("rail", track), SliderOrientation::FollowTrack);
  const FrameIndex yaw = model.addRevolute("yaw", cart, Eigen::Vector3d::UnitZ());
  const FrameIndex slide = model.addPrismatic("slide", Model::ground, Eigen::Vector3d::UnitX());
  model.addBody("body", yaw, 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  model.addBody("block", slide, 1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  model.addTrackGuidance("guidance", yaw, "cart", 400.0, 0.0);                    // Δ = yaw angle
  model.addGuidanceSpring("target", "slide", 30.0, 0.0, TimeFunction::polynomial({0.1, 0.2}));  // r(t) = 0.1 + 0.2 t
  model.addPointSpringDamper("strut", Model::ground, Eigen::Vector3d(0, 3, 4), slide, Eigen::Vector3d::Zero(), 50.0,
                             0.0, 2.0);                                            // ℓ = |(x, −3, −4)|
  Workspace<double> ws(model);
  const double s = 2.0, phi = 0.4, x = 1.5, t = 2.0;
  const Eigen::VectorXd q = Eigen::Vector3d(s, phi, x), v = Eigen::VectorXd::Zero(3);
  const MechanicalEnergy energy = mechanicalEnergy(model, ws, q, v, t);
  const double length = std::sqrt(x * x + 9.0 + 16.0);
  const double expected = 0.5 * 400.0 * phi * phi + 0.5 * 30.0 * std::pow(x - 0.1 - 0.2 * t, 2) +
                          0.5 * 50.0 * std::pow(length - 2.0, 2);
  EXPECT_NEAR(energy.springs, expected, 1e-13 * expected);
  EXPECT_EQ(energy.kinetic, 0.0);
  EXPECT_EQ(energy.gravity, 0.0);  // no gravity
}

/// The scene text with `extra` appended to its last section (the sensors).
LoadedScene withSensors(const std::string& scene, const std::string& extra) {
  const SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + scene + ".yaml");
  return loadScene({source.path, source.text + extra});
}

// Mass 2 kg on a prismatic joint, a joint spring (k₁ = 50 N/m) and a point spring (k₂ = 80 N/m,
// rest 0.8 m) from the ground point (−1, 0, 0), ℓ = 1 + x: a linear, undamped system. The
// trapezoidal rule (β = ¼, γ = ½) conserves the energy of a linear system exactly: with
// Δq = h(vₙ + vₙ₊₁)/2 and M(vₙ₊₁ − vₙ) = −h K(qₙ + qₙ₊₁)/2 the kinetic change is −Δqᵀ K (qₙ + qₙ₊₁)/2, the
// potential change +Δqᵀ K (qₙ + qₙ₊₁)/2. What remains is round-off (1e-16 per step over 2000 steps)
// and Newton's last increment on a linear problem (round-off too): 1e-11 of E₀ is far above both.
TEST(EnergySensor, UndampedSpringMassConservesEnergyExactly) {
  const char* text =
      "settings: {step: 1.0e-3, end_time: 2.0}\n"
      "elements:\n"
      "  - {name: slide, type: prismatic, parent: ground, axis: [1, 0, 0], q0: 0.1, v0: 0.5}\n"
      "bodies:\n"
      "  - {name: block, frame: slide, mass: 2.0, Ixx: 0.1, Iyy: 0.1, Izz: 0.1}\n"
      "forces:\n"
      "  - {name: spring, type: joint_spring_damper, joint: slide, k: 50}\n"
      "  - {name: strut, type: point_spring_damper, frame_a: ground, point_a: [-1, 0, 0], frame_b: slide,\n"
      "     k: 80, rest_length: 0.8}\n"
      "sensors:\n"
      "  - {name: E, type: energy}\n"
      "  - {name: T, type: energy, part: kinetic}\n"
      "  - {name: V, type: energy, part: potential}\n";
  const Scene scene = loadScene({"spring_mass.yaml", text}).scene;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const Eigen::MatrixXd sensors = sensorHistory(scene.model, trajectory);
  const double e0 = 0.5 * 2.0 * 0.25 + 0.5 * 50.0 * 0.01 + 0.5 * 80.0 * 0.3 * 0.3;
  EXPECT_NEAR(sensors(0, 0), e0, 1e-15 * e0);
  for (Eigen::Index k = 0; k < sensors.rows(); ++k) {
    ASSERT_NEAR(sensors(k, 0), e0, 1e-11 * e0) << "t = " << trajectory.time[k];
    ASSERT_NEAR(sensors(k, 1) + sensors(k, 2), sensors(k, 0), 1e-15 * e0);
  }
  // Energy really moves between its parts: ω = √(130/2), amplitude ≈ 0.12 m.
  EXPECT_LT(sensors.col(1).minCoeff(), 0.01 * e0);
}

// The shipped pendulum (I_O = 1.001 kg m², m g L = 9.81 J) released at 90°, E = 0 at the start
// (the bob at the height of the ground origin). For one degree of freedom with constant inertia
// the trapezoidal rule's energy balance is exact up to the quadrature error of ∫V'dq (Newmark
// β = ¼, γ = ½: Δq = h(vₙ + vₙ₊₁)/2 and I(vₙ₊₁ − vₙ) = −h(V'ₙ + V'ₙ₊₁)/2 give ΔT = −Δq(V'ₙ + V'ₙ₊₁)/2):
//     |Eₙ₊₁ − Eₙ| ≤ |Δq|³/12 max|V'''| ≤ (h v_max)³/12 · m g L,   V''' = m g L sin q,
// with v_max = √(2 m g L / I_O) (+1 % for the discrete energy). Over N steps: N times that.
TEST(EnergySensor, PendulumEnergyStaysWithinTheTrapezoidalBound) {
  const Scene scene = withSensors("pendulum", "  - {name: E, type: energy}\n").scene;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const Eigen::MatrixXd sensors = sensorHistory(scene.model, trajectory);
  const Eigen::Index column = scene.model.sensor("E");
  const double mgl = 9.81, h = scene.settings.step;
  const double v_max = 1.01 * std::sqrt(2.0 * mgl / 1.001);
  const double per_step = std::pow(h * v_max, 3) / 12.0 * mgl;
  EXPECT_NEAR(sensors(0, column), 0.0, 1e-14);
  for (Eigen::Index k = 0; k < sensors.rows(); ++k)
    ASSERT_LE(std::abs(sensors(k, column)), static_cast<double>(k) * per_step + 1e-12) << "t = " << trajectory.time[k];
}

// The design gradients differentiate sensors of the state alone; an energy sensor depends on the
// masses and stiffnesses directly, so a design problem refuses it, at the line of its `sensor:`.
TEST(EnergySensor, DesignProblemRefusesItAsCost) {
  const char* text =
      "elements:\n"                                                                              // 1
      "  - {name: slide, type: prismatic, parent: ground, axis: [1, 0, 0], q0: 0.1}\n"          // 2
      "bodies:\n"                                                                                // 3
      "  - {name: block, frame: slide, mass: 2.0, Ixx: 0.1, Iyy: 0.1, Izz: 0.1}\n"              // 4
      "forces:\n"                                                                                // 5
      "  - {name: spring, type: joint_spring_damper, joint: slide, k: 50}\n"                    // 6
      "sensors:\n"                                                                               // 7
      "  - {name: E, type: energy}\n"                                                            // 8
      "design:\n"                                                                                // 9
      "  variables: [{parameter: spring.k, lower: 10, upper: 100}]\n"                            // 10
      "  cost: {sensor: E}\n"                                                                     // 11
      "  artificial: {initial: 1, lower: 0, upper: 10}\n";                                       // 12
  try {
    loadDesignProblem({"energy_cost.yaml", text});
    FAIL() << "an energy sensor was accepted as a cost";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 11) << e.what();
    EXPECT_NE(e.reason().find("sensor 'E' is an energy sensor"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("cannot be a cost or a constraint"), std::string::npos) << e.what();
  }
}

// The energy and cut-reaction sensors read the model's parameters and λ besides the kinematics; the
// step records them on the kinematics it already has, sensorHistory computes every stored state's
// kinematics again. Same arithmetic on the same state: equal to the last bit, on a closed loop (the
// four-bar, whose step projects its rates) as on an open chain (the pendulum).
TEST(EnergySensor, RecordedInTheStepAsSensorHistoryComputesThem) {
  const std::string extra =
      "  - {name: E, type: energy}\n  - {name: T, type: energy, part: kinetic}\n";
  for (const auto& [name, more] : {std::pair<const char*, std::string>{"pendulum", ""},
                                   {"four_bar", "  - {name: F, type: cut_force, cut: loop, component: y}\n"}}) {
    const Scene scene = withSensors(name, extra + more).scene;
    const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
    const Eigen::MatrixXd recomputed = sensorHistory(scene.model, trajectory);
    ASSERT_EQ(trajectory.sensors.rows(), recomputed.rows()) << name;
    ASSERT_EQ(trajectory.sensors.cols(), recomputed.cols()) << name;
    EXPECT_EQ((trajectory.sensors - recomputed).cwiseAbs().maxCoeff(), 0.0) << name;
  }
}

}  // namespace
}  // namespace mbsopt
