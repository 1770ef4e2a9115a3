// The shipped scene files (problems/scenes/*.yaml), loaded and simulated as the command line does,
// against closed-form facts of the mechanisms they describe (each file's header states them):
//   pendulum         the large-amplitude period 4K(sin(φ₀/2))/ω₀ and the trapezoidal rule's energy error
//   double_pendulum  tip kinematics of the chain, the initial energy, energy conservation at O(h²)
//   slider_crank     the slider position and speed against s(θ) at every step, closure at round-off
//   four_bar         energy conservation at O(h²) without drift, closure at round-off
// and, for every file, the naming contract of problems/scenes/README.md: the dotted parameters of the
// file include every Model::parameterNames() entry, with the model's value.
//
// The expected values are computed here from the numbers written in the files (repeated below as
// constants, and checked against the loaded model), independently of the library's kinematics.
#include <gtest/gtest.h>

#include "tests/closed_forms.hpp"
#include "tests/mechanical_energy.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/mass_matrix.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/integrators/trajectory.hpp"
#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {
namespace {

using test::Energy;
using test::mechanicalEnergy;

constexpr double kPi = 3.14159265358979323846;
constexpr double kGravity = 9.81;

std::string scenePath(const std::string& name) {
  return std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml";
}

/// A shipped scene as loaded from its file.
struct ShippedScene {
  SceneSource source;
  LoadedScene loaded;
  explicit ShippedScene(const std::string& name) : source(readSceneFile(scenePath(name))), loaded(loadScene(source)) {}
};

/// A shipped scene and its run with the file's own settings.
struct ShippedRun {
  const LoadedScene& loaded;
  Trajectory trajectory;
  Eigen::MatrixXd sensors;  ///< rows = time points, columns = the model's sensors

  explicit ShippedRun(const LoadedScene& scene)
      : loaded(scene),
        trajectory(NewmarkIntegrator(scene.scene.model, scene.scene.settings).simulate(scene.scene.q0, scene.scene.v0)),
        sensors(sensorHistory(scene.scene.model, trajectory)) {}
  const Model& model() const { return loaded.scene.model; }
  Eigen::VectorXd sensor(const std::string& name) const { return sensors.col(model().sensor(name)); }
};

/// Loading and above all simulating are the expensive part: each is done once per test process
/// (ctest runs every test in its own process, a plain run shares them between tests).
const LoadedScene& loadShipped(const std::string& name) {
  static std::map<std::string, std::unique_ptr<ShippedScene>> scenes;
  auto& scene = scenes[name];
  if (!scene) scene = std::make_unique<ShippedScene>(name);
  return scene->loaded;
}
const ShippedRun& shipped(const std::string& name) {
  static std::map<std::string, std::unique_ptr<ShippedRun>> runs;
  auto& run = runs[name];
  if (!run) run = std::make_unique<ShippedRun>(loadShipped(name));
  return *run;
}

/// The same scene run with step 2h (everything else as in the file).
Trajectory runWithDoubleStep(const Scene& scene) {
  NewmarkSettings settings = scene.settings;
  settings.step *= 2.0;
  return NewmarkIntegrator(scene.model, settings).simulate(scene.q0, scene.v0);
}

struct EnergyError {
  double max_deviation = 0.0;   ///< max |E(t) − E(0)| over the run [J]
  double first_quarter = 0.0;   ///< the same over the first and the last quarter of the run
  double last_quarter = 0.0;
  double max_kinetic = 0.0;     ///< the energy scale of the motion [J]
  double max_rate = 0.0;        ///< max |q̇ᵢ| over the run [rad/s]
};

EnergyError energyError(const Model& model, const Trajectory& trajectory) {
  const Eigen::Index points = trajectory.time.size();
  Workspace<double> ws(model);
  const double initial = mechanicalEnergy(model, ws, trajectory.q.col(0), trajectory.v.col(0)).total();
  EnergyError error;
  for (Eigen::Index k = 0; k < points; ++k) {
    const Energy e = mechanicalEnergy(model, ws, trajectory.q.col(k), trajectory.v.col(k));
    const double deviation = std::abs(e.total() - initial);
    error.max_deviation = std::max(error.max_deviation, deviation);
    if (k < points / 4) error.first_quarter = std::max(error.first_quarter, deviation);
    if (k >= points - points / 4) error.last_quarter = std::max(error.last_quarter, deviation);
    error.max_kinetic = std::max(error.max_kinetic, e.kinetic);
    error.max_rate = std::max(error.max_rate, trajectory.v.col(k).cwiseAbs().maxCoeff());
  }
  return error;
}

/// The energy error of the trapezoidal rule (Newmark β = 1/4, γ = 1/2) on a conservative system,
/// from the file's run (step h) and a run with step 2h.
///
/// Order. The rule is second order and symmetric; on a reversible mechanical system it keeps a
/// modified energy Ẽ = E + h² E₂(q, q̇) + O(h⁴) up to round-off, so E(t) − E(0) = h² e₂(t) + O(h⁴)
/// with e₂ bounded along the motion: a bounded O(h²) oscillation, no drift (the pendulum test
/// below derives e₂ in closed form). Doubling h therefore multiplies max |E − E₀| by 4 up to
/// relative O((Ωh)²) ~ 5e-4 and the O(h²) shift of the trajectory: we accept [3.6, 4.4].
/// Numerical dissipation (first order) would give 2, an h-independent error (e.g. from the
/// constraint projections) 1.
///
/// Size. For the pendulum max |E − E₀| = (ω₀h)²(1 − cos φ₀)/12 · E₀ = (Ωh)²/24 · max T, Ω the
/// largest rate. For a chain or a loop, M(q) and the constraint geometry vary faster than a single
/// pendulum's potential, which scales the coefficient up (measured 0.033 for the double pendulum,
/// 0.2 for the four-bar); we bound it by 1/2, 12× the pendulum's.
void expectSecondOrderEnergyError(const EnergyError& at_h, const EnergyError& at_2h, double h) {
  EXPECT_LE(at_h.max_deviation, 0.5 * std::pow(at_h.max_rate * h, 2) * at_h.max_kinetic)
      << "max rate " << at_h.max_rate << " rad/s, max T " << at_h.max_kinetic << " J";
  const double ratio = at_2h.max_deviation / at_h.max_deviation;
  EXPECT_GE(ratio, 3.6) << "h: " << at_h.max_deviation << " J, 2h: " << at_2h.max_deviation << " J";
  EXPECT_LE(ratio, 4.4) << "h: " << at_h.max_deviation << " J, 2h: " << at_2h.max_deviation << " J";
}

using test::ellipticK;

// ============================== every scene ==============================

class EveryShippedScene : public ::testing::TestWithParam<const char*> {};

INSTANTIATE_TEST_SUITE_P(Scenes, EveryShippedScene,
                         ::testing::Values("pendulum", "double_pendulum", "slider_crank", "four_bar"));

TEST_P(EveryShippedScene, DottedParametersIncludeEveryModelParameterWithItsValue) {
  const SceneSource source = readSceneFile(scenePath(GetParam()));
  const Model model = loadScene(source).scene.model;
  const std::vector<std::pair<std::string, double>> parameters = sceneParameters(source);
  const std::vector<std::string> names = model.parameterNames();
  ASSERT_FALSE(names.empty());
  for (const std::string& name : names) {
    const auto found = std::find_if(parameters.begin(), parameters.end(),
                                    [&](const auto& parameter) { return parameter.first == name; });
    if (found == parameters.end()) {
      ADD_FAILURE() << GetParam() << ": the model parameter '" << name << "' is not a dotted parameter of the file";
      continue;
    }
    // Parameters the file leaves out (a default com, unset gravity components) must still be
    // named, with the default the model holds; numbers are read once, so equality is exact.
    EXPECT_EQ(found->second, model.parameter(name)) << GetParam() << ": " << name;
  }
}

TEST_P(EveryShippedScene, IsBuiltIntoTheLibraryUnderItsBaseName) {
  const std::optional<SceneSource> builtin = builtinScene(GetParam());
  ASSERT_TRUE(builtin.has_value()) << GetParam();
  EXPECT_EQ(builtin->text, readSceneFile(scenePath(GetParam())).text);
}

TEST_P(EveryShippedScene, OnlyTheSliderCrankStartsOffItsLoop) {
  // slider_crank.yaml rounds its initial coordinates on purpose (see its header); the others are
  // exact (the four-bar to round-off, a correction of ~1e-16 m that must not be reported).
  const LoadedScene& scene = loadShipped(GetParam());
  if (std::string(GetParam()) == "slider_crank") {
    EXPECT_FALSE(scene.warnings.empty());
  } else {
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  }
}

TEST_P(EveryShippedScene, SensorsRecordedInTheStepAreThoseOfTheStoredStates) {
  // sensorHistory computes the kinematics of every stored (q, q̇, q̈) again from scratch; the step
  // evaluates the sensors on the geometry it already has. Same arithmetic on the same state: the
  // values must agree to the last bit.
  const ShippedRun& run = shipped(GetParam());
  ASSERT_GT(run.sensors.cols(), 0);
  ASSERT_EQ(run.trajectory.sensors.rows(), run.sensors.rows());
  ASSERT_EQ(run.trajectory.sensors.cols(), run.sensors.cols());
  EXPECT_EQ((run.trajectory.sensors - run.sensors).cwiseAbs().maxCoeff(), 0.0);
}

// ============================== pendulum ==============================
// pendulum.yaml: m = 1 kg at L = 1 m, I_c = 0.001 kg m², released from rest at φ₀ = 90°.

struct PendulumData {
  double mass = 1.0, length = 1.0, inertia = 0.001, amplitude = 0.5 * kPi;
  double pivotInertia() const { return inertia + mass * length * length; }
  double smallAngleFrequency() const { return std::sqrt(mass * kGravity * length / pivotInertia()); }
  double period() const { return 4.0 * ellipticK(std::sin(0.5 * amplitude)) / smallAngleFrequency(); }
  /// ½ I_O φ̇² + m g L (1 − cos φ): zero at the hanging rest state.
  double energy(double angle, double rate) const {
    return 0.5 * pivotInertia() * rate * rate + mass * kGravity * length * (1.0 - std::cos(angle));
  }
};

TEST(ShippedPendulum, FileHoldsTheDocumentedData) {
  const PendulumData p;
  const ShippedRun& run = shipped("pendulum");
  EXPECT_EQ(run.model().parameter("bob.mass"), p.mass);
  EXPECT_EQ(run.model().parameter("bob.com.y"), -p.length);
  EXPECT_EQ(run.model().parameter("bob.Izz"), p.inertia);
  EXPECT_EQ(run.model().parameter("gravity.y"), -kGravity);
  EXPECT_DOUBLE_EQ(run.loaded.scene.q0[0], p.amplitude);  // 90 deg
  // The bob sensors are the circle of radius L at the joint angle (round-off).
  const Eigen::VectorXd angle = run.sensor("angle"), x = run.sensor("bob_x"), y = run.sensor("bob_y");
  for (Eigen::Index k = 0; k < angle.size(); ++k) {
    ASSERT_NEAR(x[k], p.length * std::sin(angle[k]), 1e-14);
    ASSERT_NEAR(y[k], -p.length * std::cos(angle[k]), 1e-14);
  }
}

TEST(ShippedPendulum, PeriodIsTheLargeAmplitudeClosedForm) {
  const PendulumData p;
  const ShippedRun& run = shipped("pendulum");
  const Trajectory& traj = run.trajectory;
  // Zero crossings of φ (both ways) are half a period apart; linear interpolation between samples.
  // At φ = 0, φ̈ = −ω₀² sin φ = 0, so the chord's error in the crossing time is O(|φ⃛| h³/|φ̇|) ~ 1e-9 s.
  std::vector<double> crossings;
  for (Eigen::Index n = 1; n < traj.time.size(); ++n) {
    const double before = traj.q(0, n - 1), after = traj.q(0, n);
    if ((before > 0.0) != (after > 0.0))
      crossings.push_back(traj.time[n - 1] + (traj.time[n] - traj.time[n - 1]) * before / (before - after));
  }
  ASSERT_GE(crossings.size(), 4u) << "the run should cover two periods";
  const double measured = 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double exact = p.period();  // 2.3690 s, 18 % longer than the small-angle 2π/ω₀ = 2.0071 s
  const double w0 = p.smallAngleFrequency(), h = run.loaded.scene.settings.step;

  // The trapezoidal rule lengthens the period: for a linear oscillator of frequency ω by
  // (ωh)²/12 (ω_h = (2/h) atan(ωh/2)). The pendulum's linearised frequency √(ω₀² cos φ) never
  // exceeds ω₀, so its elongation lies in [0, (ω₀h)²/12] = [0, 8.2e-7] (an independent scalar
  // Newmark computation gives 0.0571 (ω₀h)² = 5.6e-7 at 90°, ≈ (2πh/T)²/12). The crossing
  // interpolation (~1e-9 s over 1.5 periods) and the Newton tolerance (1e-10 relative) add < 1e-8.
  // The window is tight: leaving out the sphere's own 0.001 kg m² (5e-4 of T) would miss it 600×.
  const double relative = measured / exact - 1.0;
  EXPECT_GE(relative, -1e-8) << "measured " << measured << " s, closed form " << exact << " s";
  EXPECT_LE(relative, w0 * w0 * h * h / 12.0 + 1e-8) << "measured " << measured << " s, closed form " << exact << " s";
}

TEST(ShippedPendulum, EnergyErrorIsTheTrapezoidalOscillation) {
  const PendulumData p;
  const ShippedRun& run = shipped("pendulum");
  const Trajectory& traj = run.trajectory;
  const double e0 = p.energy(traj.q(0, 0), traj.v(0, 0));
  EXPECT_NEAR(e0, p.mass * kGravity * p.length, 1e-12);  // released from rest at 90°: E = m g L
  double worst = 0.0;
  for (Eigen::Index n = 0; n < traj.time.size(); ++n)
    worst = std::max(worst, std::abs(p.energy(traj.q(0, n), traj.v(0, n)) - e0) / e0);

  // The trapezoidal rule gives ½I_O(vₙ₊₁² − vₙ²) = −½(V'(qₙ) + V'(qₙ₊₁))Δq: each step changes E by
  // the trapezoidal quadrature error of −∫V'dq, −V'''Δq³/12. Summed along a swing,
  // E − E₀ ≈ −(h²/12)∫V'''(φ) φ̇² dφ, which cancels over a swing (V''' odd, φ̇² even: no drift) and
  // peaks at the bottom at (h²/12)(mgL)²(1 − cos φ₀)²/I_O, i.e. relative to E₀ = mgL(1 − cos φ₀)
  //     max |E − E₀|/E₀ ≈ (ω₀h)²(1 − cos φ₀)/12 = 8.2e-7 here.
  // Its O(h⁴) remainder is ~(ω₀h)² ≈ 1e-5 of it and the Newton tolerance adds ~1e-12: the band
  // [0.9, 1.1] × prediction checks both the size and that it is the trapezoidal rule's error.
  const double w0 = p.smallAngleFrequency(), h = run.loaded.scene.settings.step;
  const double predicted = w0 * w0 * h * h * (1.0 - std::cos(p.amplitude)) / 12.0;
  EXPECT_LE(worst, 1.1 * predicted);
  EXPECT_GE(worst, 0.9 * predicted);
}

// ============================== double pendulum ==============================
// double_pendulum.yaml: links of L = 1 m, masses 1.2 and 0.6 kg with centres at 0.5 m,
// released from rest at shoulder 90°, elbow 0.

TEST(ShippedDoublePendulum, IsATreeWithoutClosureEquations) {
  const ShippedRun& run = shipped("double_pendulum");
  EXPECT_EQ(run.model().coordinateCount(), 2);
  EXPECT_EQ(run.model().constraintCount(), 0);
  EXPECT_TRUE(run.model().cuts().empty());
  EXPECT_EQ(run.trajectory.lambda.rows(), 0);
  EXPECT_EQ(run.trajectory.closure_error.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(run.loaded.scene.v0.isZero(0.0));  // released from rest
}

TEST(ShippedDoublePendulum, TipSensorsFollowTheChainGeometry) {
  // tip = L₁(sin θ₁, −cos θ₁) + L₂(sin θ₂, −cos θ₂), θ₁ = q₁, θ₂ = q₁ + q₂: products of O(1)
  // terms, round-off ~1e-16 m; 1e-13 m allows for the rotation matrices' accumulation.
  const ShippedRun& run = shipped("double_pendulum");
  const Eigen::VectorXd x = run.sensor("tip_x"), y = run.sensor("tip_y");
  const Eigen::VectorXd shoulder = run.sensor("shoulder_angle"), elbow = run.sensor("elbow_angle");
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const double q1 = run.trajectory.q(0, k), q2 = run.trajectory.q(1, k);
    ASSERT_EQ(shoulder[k], q1);
    ASSERT_EQ(elbow[k], q2);
    ASSERT_NEAR(x[k], std::sin(q1) + std::sin(q1 + q2), 1e-13) << "t = " << run.trajectory.time[k];
    ASSERT_NEAR(y[k], -std::cos(q1) - std::cos(q1 + q2), 1e-13) << "t = " << run.trajectory.time[k];
  }
  // It really swings: the tip passes below the pivot and the elbow bends far.
  EXPECT_LT(y.minCoeff(), -1.5);
  EXPECT_GT(elbow.cwiseAbs().maxCoeff(), 0.5);
}

TEST(ShippedDoublePendulum, InitialEnergyIsTheClosedForm) {
  // Above the hanging rest state, at rest with both links horizontal:
  // E = g (m₁ c₁ + m₂ (L₁ + c₂)) = 9.81 (1.2·0.5 + 0.6·1.5) = 14.715 J. Round-off only.
  const Scene& scene = loadShipped("double_pendulum").scene;
  const Eigen::VectorXd hanging = Eigen::VectorXd::Zero(2);
  Workspace<double> ws(scene.model);
  const double above_rest = mechanicalEnergy(scene.model, ws, scene.q0, scene.v0).total() -
                            mechanicalEnergy(scene.model, ws, hanging, hanging).total();
  EXPECT_NEAR(above_rest, kGravity * (1.2 * 0.5 + 0.6 * 1.5), 1e-12);
}

TEST(ShippedDoublePendulum, EnergyIsConservedToSecondOrderInTheStep) {
  const ShippedRun& run = shipped("double_pendulum");
  const EnergyError at_h = energyError(run.model(), run.trajectory);  // the file's step h
  const EnergyError at_2h = energyError(run.model(), runWithDoubleStep(run.loaded.scene));
  // The motion is not periodic, so no drift test over quarters (its later swings need not resemble
  // the first ones); the h and 2h runs stay close over 3 s.
  expectSecondOrderEnergyError(at_h, at_2h, run.loaded.scene.settings.step);
}

// ============================== slider-crank ==============================
// slider_crank.yaml: r = 0.1 m, l = 0.4 m, rail at e = 0.05 m, θ(t) = 10 t.

struct SliderCrankData {
  double r = 0.1, l = 0.4, e = 0.05, w = 10.0;
  double root(double theta) const { return std::sqrt(l * l - std::pow(r * std::sin(theta) - e, 2)); }
  double position(double theta) const { return r * std::cos(theta) + root(theta); }
  double speed(double theta) const {
    return -r * w * (std::sin(theta) + std::cos(theta) * (r * std::sin(theta) - e) / root(theta));
  }
};

TEST(ShippedSliderCrank, AssemblyWarningSaysHowFar) {
  const LoadedScene& loaded = loadShipped("slider_crank");
  // One warning for the coordinates (off by 3.73e-5 m at the slider), one for the rates (off by
  // 2.4e-4 rad/s at the rod); each names the coordinate moved most.
  ASSERT_EQ(loaded.warnings.size(), 2u);
  EXPECT_NE(loaded.warnings[0].find("'slider'"), std::string::npos) << loaded.warnings[0];
  EXPECT_NE(loaded.warnings[1].find("'conrod'"), std::string::npos) << loaded.warnings[1];
  // The file is off by 3.7e-5 m on the slider and 1.3e-5 rad on the rod (see its header); after
  // assembly the initial state is on the loop at θ = 0.
  const SliderCrankData d;
  const Scene& scene = loaded.scene;
  const int slider = scene.model.coordinate("slider"), conrod = scene.model.coordinate("conrod");
  EXPECT_NEAR(scene.q0[slider], d.position(0.0), 1e-12);
  EXPECT_NEAR(scene.q0[conrod], std::asin(d.e / d.l), 1e-12);
  // The rates are projected too: ṡ from the closed form, the rod's relative rate −r w/(l cos φ) − w.
  EXPECT_NEAR(scene.v0[slider], d.speed(0.0), 1e-10);
  EXPECT_NEAR(scene.v0[conrod], -d.r * d.w / (d.l * std::cos(std::asin(d.e / d.l))) - d.w, 1e-10);
}

TEST(ShippedSliderCrank, SliderFollowsTheClosedFormAtEveryStep) {
  const SliderCrankData d;
  const ShippedRun& run = shipped("slider_crank");
  const Trajectory& traj = run.trajectory;
  const Eigen::VectorXd crank = run.sensor("crank_angle"), x = run.sensor("slider_x"), v = run.sensor("slider_v");
  ASSERT_EQ(run.model().drivenCoordinates().size(), 1u);
  EXPECT_GT(crank[crank.size() - 1], 2.0 * kPi) << "the run covers more than a revolution";
  double worst_position = 0.0, worst_speed = 0.0;
  for (Eigen::Index k = 0; k < traj.time.size(); ++k) {
    // The crank is driven exactly (θ = w t, evaluated as a polynomial: round-off).
    ASSERT_NEAR(crank[k], d.w * traj.time[k], 1e-12);
    // No degree of freedom is left: s is a function of θ through the loop alone. First order in
    // the closure residual b = (b_x, b_y): b_y = l cos φ δφ, b_x = −l sin φ δφ − δs, so
    // |δs| ≤ (1 + |tan φ|) ‖b‖∞ ≤ 1.41 ‖b‖∞ since |sin φ| ≤ (r + e)/l = 0.375. Plus round-off
    // in s and in the formula (~1e-16 m): 1.5 ‖b‖∞ + 1e-14 m.
    const double position_error = std::abs(x[k] - d.position(crank[k]));
    ASSERT_LE(position_error, 1.5 * traj.closure_error[k] + 1e-14) << "t = " << traj.time[k];
    worst_position = std::max(worst_position, position_error);
    // Velocities are projected onto B q̇ = −∂b/∂t after each step, which for a mechanism without
    // degree of freedom fixes q̇ from the crank rate exactly. The residual error is the position
    // error carried through B (~1e-15 × rates ~10) and round-off: 1e-12 m/s, on speeds ~1 m/s.
    const double speed_error = std::abs(v[k] - d.speed(crank[k]));
    ASSERT_LE(speed_error, 1e-12) << "t = " << traj.time[k];
    worst_speed = std::max(worst_speed, speed_error);
  }
  // The slider reaches its extreme positions √((l ± r)² − e²), where rod and crank are aligned
  // (at t = 0.0100 s and 0.331 s). Near a turning point s is quadratic in t, so the nearest
  // sample misses it by at most ½|s̈|(h/2)² ≤ ½ × 13 m/s² × (0.5 ms)² = 1.6e-6 m: 1e-5 m.
  EXPECT_NEAR(x.maxCoeff(), std::sqrt(std::pow(d.l + d.r, 2) - d.e * d.e), 1e-5);
  EXPECT_NEAR(x.minCoeff(), std::sqrt(std::pow(d.l - d.r, 2) - d.e * d.e), 1e-5);
  RecordProperty("worst_position_error", std::to_string(worst_position));
  RecordProperty("worst_speed_error", std::to_string(worst_speed));
}

TEST(ShippedSliderCrank, ClosureErrorStaysAtRoundOff) {
  // Position-level closure is solved by Newton with the rest of the step; its last correction
  // leaves b quadratic in an increment βh²Δq̈ ≲ 2.5e-7 × 1e-10 (1 + |q̈|): nothing but round-off of
  // b (ulps of 0.5 m, ~1e-16 m) survives. 1e-13 m is 1000 ulps.
  const ShippedRun& run = shipped("slider_crank");
  EXPECT_EQ(run.model().constraintCount(), 3);  // the spherical cut's z equation vanishes in the plane
  EXPECT_LE(run.trajectory.closure_error.maxCoeff(), 1e-13);
  EXPECT_LE(run.trajectory.statistics.max_closure_error, 1e-13);
}

// ============================== four-bar ==============================

TEST(ShippedFourBar, StartsClosedOnTheDocumentedBranch) {
  // The file's state is exact: crank at 0°, coupler at acos(0.6) relative to it, rocker at 90°,
  // which puts the coupler's end at C = (1, 0.8) (products of O(1) numbers: round-off).
  const Scene& scene = loadShipped("four_bar").scene;
  EXPECT_NEAR(scene.q0[scene.model.coordinate("crank")], 0.0, 1e-14);
  EXPECT_NEAR(scene.q0[scene.model.coordinate("coupler")], std::acos(0.6), 1e-14);
  EXPECT_NEAR(scene.q0[scene.model.coordinate("rocker")], 0.5 * kPi, 1e-14);
  Workspace<double> ws(scene.model);
  forwardKinematics(scene.model, ws, scene.q0, scene.v0, scene.v0, KinematicsLevel::Position);
  const Eigen::Vector3d c = ws.position[static_cast<std::size_t>(scene.model.frame("coupler_tip"))];
  EXPECT_LE((c - Eigen::Vector3d(1.0, 0.8, 0.0)).cwiseAbs().maxCoeff(), 1e-14) << c.transpose();
  EXPECT_EQ(scene.model.constraintCount(), 5);
}

TEST(ShippedFourBar, ClosureErrorStaysAtRoundOff) {
  // As for the slider-crank: Newton on the position-level closure leaves round-off (ulps of
  // coordinates ~1 m, amplified by the rank-2 solve's condition number, O(10)). 1e-13 m.
  const ShippedRun& run = shipped("four_bar");
  EXPECT_LE(run.trajectory.closure_error.maxCoeff(), 1e-13);
  // The coupler point C stays on the rocker's circle of radius 0.8 m about D = (1, 0).
  const Eigen::VectorXd x = run.sensor("joint_c_x"), y = run.sensor("joint_c_y");
  for (Eigen::Index k = 0; k < x.size(); ++k)
    ASSERT_NEAR(std::hypot(x[k] - 1.0, y[k]), 0.8, 1e-13) << "t = " << run.trajectory.time[k];
  // It does swing, widely: the crank falls through more than 180° (to −208° measured) and the
  // rocker turns by more than 45°, so the loop is exercised over much of its range.
  const Eigen::VectorXd crank = run.sensor("crank_angle"), rocker = run.sensor("rocker_angle");
  EXPECT_LT(crank.minCoeff(), -kPi);
  EXPECT_GT(rocker.maxCoeff() - rocker.minCoeff(), 0.25 * kPi);
}

TEST(ShippedFourBar, EnergyIsConservedToSecondOrderWithoutDrift) {
  const ShippedRun& run = shipped("four_bar");
  const EnergyError at_h = energyError(run.model(), run.trajectory);  // the file's step h
  const EnergyError at_2h = energyError(run.model(), runWithDoubleStep(run.loaded.scene));
  // No damping and an ideal (workless) cut joint: E is constant up to the trapezoidal rule's O(h²)
  // oscillation. The linkage swings back and forth (about 2 swings in 4 s), repeating its error:
  // the last quarter may not be markedly worse than the first, as a drift from the projections or
  // numerical dissipation would make it.
  expectSecondOrderEnergyError(at_h, at_2h, run.loaded.scene.settings.step);
  EXPECT_LE(at_h.last_quarter, 1.5 * at_h.first_quarter)
      << "first quarter " << at_h.first_quarter << " J, last quarter " << at_h.last_quarter << " J";
}

}  // namespace
}  // namespace mbsopt
