// The `cut_force` sensor (problems/scenes/README.md, "Sensors"): the reaction a cut joint transmits
// to its frame b, from the multipliers λ, in the axes of its frame a, against Newton's laws on the
// body the cut holds; and as a design response, with its exact gradients.
#include <gtest/gtest.h>

#include <cmath>

#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/sensitivity/continuous_adjoint.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/gradient_checks.hpp"

namespace mbsopt {
namespace {

struct CutRun {
  Scene scene;
  Trajectory trajectory;
  Eigen::MatrixXd sensors;
  double column(const std::string& name, Eigen::Index k) const { return sensors(k, scene.model.sensor(name)); }
};

CutRun simulate(const std::string& text) {
  CutRun run{loadScene({"cut_force.yaml", text}).scene, {}, {}};
  run.trajectory = NewmarkIntegrator(run.scene.model, run.scene.settings).simulate(run.scene.q0, run.scene.v0);
  run.sensors = sensorHistory(run.scene.model, run.trajectory);
  return run;
}

constexpr double kG = 9.81;

// A 3 kg block on a vertical prismatic joint, held by a spherical cut to a ground frame turned by
// 90° about x (its y axis is the ground z): at rest, the cut carries the weight, m g = 29.43 N up,
// which is +y in frame a's axes. The multipliers solve M q̈ + h − Q + Bᵀλ = 0 to Newton's tolerance
// (1e-10 relative): 1e-9 N is far above that and far below any sign or axis error.
TEST(CutForceSensor, BlockHeldAtRestCarriesItsWeightInFrameAAxes) {
  const CutRun run = simulate(
      "settings: {step: 1.0e-3, end_time: 0.1}\n"
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: anchor, type: offset, parent: ground, rotation: {axis: [1, 0, 0], angle: 90 deg}}\n"
      "  - {name: lift, type: prismatic, parent: ground, axis: [0, 0, 1]}\n"
      "bodies:\n"
      "  - {name: block, frame: lift, mass: 3.0, Ixx: 0.1, Iyy: 0.1, Izz: 0.1}\n"
      "cuts:\n"
      "  - {name: pin, type: spherical, frame_a: anchor, frame_b: lift}\n"
      "sensors:\n"
      "  - {name: Fx, type: cut_force, cut: pin, component: x}\n"
      "  - {name: Fy, type: cut_force, cut: pin, component: y}\n"
      "  - {name: Fz, type: cut_force, cut: pin, quantity: force, component: z}\n"
      "  - {name: Ty, type: cut_force, cut: pin, quantity: torque, component: y}\n");
  for (Eigen::Index k = 0; k < run.sensors.rows(); ++k) {
    EXPECT_NEAR(run.column("Fx", k), 0.0, 1e-9);
    EXPECT_NEAR(run.column("Fy", k), 3.0 * kG, 1e-9);
    EXPECT_NEAR(run.column("Fz", k), 0.0, 1e-9);
    EXPECT_EQ(run.column("Ty", k), 0.0);  // a spherical cut transmits no torque
  }
}

// A 2 kg arm on a revolute joint about y with its centre of mass 0.5 m along x, held horizontal by
// a weld cut to the ground. The hinge carries the force; the weld must supply the torque that
// balances gravity about the hinge: r × m g = (0.5, 0, 0) × (0, 0, −m g) = (0, 0.5 m g, 0), so the
// cut's torque on the arm is (0, −0.5 m g, 0) = −9.81 N·m about y.
TEST(CutForceSensor, WeldHoldsAnArmWithItsTorque) {
  const CutRun run = simulate(
      "settings: {step: 1.0e-3, end_time: 0.1}\n"
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: swing, type: revolute, parent: ground, axis: [0, 1, 0]}\n"
      "bodies:\n"
      "  - {name: arm, frame: swing, mass: 2.0, com: [0.5, 0, 0], Ixx: 0.01, Iyy: 0.2, Izz: 0.2}\n"
      "cuts:\n"
      "  - {name: clamp, type: weld, frame_a: ground, frame_b: swing}\n"
      "sensors:\n"
      "  - {name: Tx, type: cut_force, cut: clamp, quantity: torque, component: x}\n"
      "  - {name: Ty, type: cut_force, cut: clamp, quantity: torque, component: y}\n"
      "  - {name: Tz, type: cut_force, cut: clamp, quantity: torque, component: z}\n");
  for (Eigen::Index k = 0; k < run.sensors.rows(); ++k) {
    EXPECT_NEAR(run.column("Tx", k), 0.0, 1e-9);
    EXPECT_NEAR(run.column("Ty", k), -0.5 * 2.0 * kG, 1e-9);
    EXPECT_NEAR(run.column("Tz", k), 0.0, 1e-9);
  }
}

// A pendulum closed by a cut: a point mass m = 1.5 kg carried by two prismatic joints (x, z), and
// a massless rod of L = 1 m on a hinge about y, pinned to the mass by a spherical cut (frame a: the
// rod's end, whose z axis points from the mass to the hinge). Released from rest at θ₀ = 90°.
// - Newton's law on the mass: the cut is the only force besides gravity, F = m (a − g). With the
//   accelerations Newton solved for (a_unprojected), this holds to Newton's tolerance.
// - The rod is massless, so it carries a pure tension along itself: F_x = F_y = 0 in the rod's axes.
// - F_z against the exact tension T = m g cos θ + m L θ̇² of the simulated (θ, θ̇): the multipliers
//   of the position-level (index-3) Newmark step are those of the accelerations before their
//   projection, which are only first-order accurate in h. The error must halve with h, and stay
//   below one step's change of the tension, h max|Ṫ|, Ṫ = −3 m g sin θ θ̇ (T = m g (3 cos θ − 2 cos θ₀)).
struct PendulumTension {
  double worst_newton = 0.0, worst_transverse = 0.0, worst_tension = 0.0, largest_rate = 0.0, largest_tension = 0.0;
};

PendulumTension pendulumTension(double h) {
  const double m = 1.5, L = 1.0;
  const CutRun run = simulate(
      "settings: {step: " + std::to_string(h) + ", end_time: 3.0}\n"
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: hinge, type: revolute, parent: ground, axis: [0, 1, 0], q0: 90 deg}\n"
      "  - {name: rod_end, type: offset, parent: hinge, translation: [0, 0, -1]}\n"
      "  - {name: px, type: prismatic, parent: ground, axis: [1, 0, 0], q0: -1}\n"
      "  - {name: pz, type: prismatic, parent: px, axis: [0, 0, 1], q0: 0}\n"
      "bodies:\n"
      "  - {name: bob, frame: pz, mass: 1.5, Ixx: 0, Iyy: 0, Izz: 0}\n"
      "cuts:\n"
      "  - {name: pin, type: spherical, frame_a: rod_end, frame_b: pz}\n"
      "sensors:\n"
      "  - {name: Fx, type: cut_force, cut: pin, component: x}\n"
      "  - {name: Fy, type: cut_force, cut: pin, component: y}\n"
      "  - {name: Fz, type: cut_force, cut: pin, component: z}\n");
  const Model& model = run.scene.model;
  const int hinge = model.coordinate("hinge"), px = model.coordinate("px"), pz = model.coordinate("pz");
  const Trajectory& tr = run.trajectory;
  PendulumTension out;
  for (Eigen::Index k = 0; k < tr.time.size(); ++k) {
    const double theta = tr.q(hinge, k), rate = tr.v(hinge, k);
    // The force on the mass in ground axes, from the sensor's components in the rod's axes.
    const Eigen::Vector3d along(std::sin(theta), 0.0, std::cos(theta)), across(std::cos(theta), 0.0, -std::sin(theta));
    const Eigen::Vector3d force = run.column("Fx", k) * across + run.column("Fy", k) * Eigen::Vector3d::UnitY() +
                                  run.column("Fz", k) * along;
    const Eigen::Vector3d newton(m * tr.a_unprojected(px, k), 0.0, m * (tr.a_unprojected(pz, k) + kG));
    out.worst_newton = std::max(out.worst_newton, (force - newton).norm());
    out.worst_transverse = std::max({out.worst_transverse, std::abs(run.column("Fx", k)), std::abs(run.column("Fy", k))});
    out.worst_tension =
        std::max(out.worst_tension, std::abs(run.column("Fz", k) - (m * kG * std::cos(theta) + m * L * rate * rate)));
    out.largest_rate = std::max(out.largest_rate, std::abs(3.0 * m * kG * std::sin(theta) * rate));
    out.largest_tension = std::max(out.largest_tension, run.column("Fz", k));
  }
  return out;
}

TEST(CutForceSensor, PendulumRodTensionFollowsNewtonsLaw) {
  const double m = 1.5, h = 1e-3;
  const PendulumTension coarse = pendulumTension(h), fine = pendulumTension(h / 2);
  EXPECT_LE(coarse.worst_newton, 1e-8 * m * kG);
  EXPECT_LE(coarse.worst_transverse, 1e-8 * m * kG);
  EXPECT_LE(coarse.worst_tension, h * coarse.largest_rate);
  const double order = std::log2(coarse.worst_tension / fine.worst_tension);
  EXPECT_NEAR(order, 1.0, 0.1);
  // The bottom is reached: the tension there is 3 m g (θ₀ = 90°), up to the same first-order error.
  EXPECT_NEAR(coarse.largest_tension, 3.0 * m * kG, h * coarse.largest_rate);
}

// A cut reaction as a design response: y = c(q)·λ, with λ Newton's multipliers of each step, so
// the exact methods carry dλ/db from Newton's augmented solve (direct) or a seed on its multipliers
// (adjoint). The block held at rest carries its weight exactly at every step: λ = m g solves the
// step's linear equations for any m, so ∫F_z dt = m g τ and F_z(τ) = m g have the gradients g τ
// and g in the mass, to round-off, by every method (central differences of a linear function too).
// Its x component reads a redundant closure row (a vertical slide cannot move the block sideways):
// statically indeterminate, so a design refuses it, naming the sensor and the cut.
TEST(CutForceSensor, AHeldBlocksReactionHasTheWeightsGradientByEveryMethod) {
  const std::string scene =
      "settings: {step: 1.0e-3, end_time: 0.5}\n"
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: lift, type: prismatic, parent: ground, axis: [0, 0, 1]}\n"
      "bodies:\n"
      "  - {name: block, frame: lift, mass: 3.0, Ixx: 0.1, Iyy: 0.1, Izz: 0.1}\n"
      "cuts:\n"
      "  - {name: pin, type: spherical, frame_a: ground, frame_b: lift}\n"
      "sensors:\n"
      "  - {name: height, type: joint, joint: lift, quantity: position}\n"
      "  - {name: Fx, type: cut_force, cut: pin, component: x}\n"
      "  - {name: Fz, type: cut_force, cut: pin, component: z}\n"
      "design:\n"
      "  variables:\n"
      "    - {parameter: block.mass, lower: 1, upper: 10}\n"
      "  cost: {sensor: height, of: max_abs}\n"
      "  artificial: {initial: 1, lower: 0, upper: 10}\n"
      "  constraints:\n";
  const DesignProblem problem = loadDesignProblem(
      {"held.yaml", scene + "    - {sensor: Fz, of: integral, bound: 10}\n    - {sensor: Fz, of: final, bound: 40}\n"});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  ASSERT_EQ(functionals.size(), 4u);  // the cost's two, then ∫F_z and F_z(τ)
  const Eigen::VectorXd x = initialPoint(problem);
  const std::vector<DesignGradient> gradients{adjointGradient(problem, functionals, x),
                                              directGradient(problem, functionals, x),
                                              continuousAdjointGradient(problem, functionals, x),
                                              finiteDifferenceGradient(problem, functionals, x, 1e-4, true)};
  for (const DesignGradient& g : gradients) {
    EXPECT_NEAR(g.constraints(2, 0), kG * 0.5, 1e-11);
    EXPECT_NEAR(g.constraints(3, 0), kG, 1e-11);
  }
  try {
    loadDesignProblem({"held.yaml", scene + "    - {sensor: Fx, of: max_abs, bound: 1}\n"});
    FAIL() << "an indeterminate reaction was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 19) << e.what();  // the constraint's line
    EXPECT_NE(std::string(e.what()).find("sensor 'Fx' reads a component of the reaction of cut 'pin' that its redundant "
                                         "closure equations leave statically indeterminate"),
              std::string::npos)
        << e.what();
  }
}

/// The four-bar swinging for 1 s with the reaction of its cut in the cost (the vertical pin force's
/// peak) and in a constraint (the integral of the horizontal one), and two masses, or those and two
/// lengths, as the design.
DesignProblem fourBarPinLoads(bool lengths, double step = 1e-3) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += std::string(R"(  - {name: pin_x, type: cut_force, cut: loop, component: x}
  - {name: pin_y, type: cut_force, cut: loop, component: y}
design:
  variables:
)") + (lengths ? "    - {parameter: crank_tip.translation.x, lower: 0.3, upper: 0.5}\n"
                 "    - {parameter: rocker_tip.translation.x, lower: 0.7, upper: 0.9}\n"
               : "") +
                 R"(    - {parameter: coupler_bar.mass, lower: 1, upper: 3}
    - {parameter: rocker_bar.mass, lower: 1, upper: 3}
  cost: {sensor: pin_y, of: max_abs}
  artificial: {initial: 1, lower: 0, upper: 200}
  constraints:
    - {sensor: pin_x, of: integral, bound: -1}
  transcription: {measure: positive_part}
)";
  return loadDesignProblem(source, {{"settings.end_time", 1.0}, {"settings.step", step}});
}

// A dynamic loop: the pin forces depend on the lengths through B, the closure and the initial state,
// on the masses through M and gravity. Adjoint = direct to round-off (≤ 1e-9 relative, as in
// test_exact_gradients; measured 4e-12); both = central differences at the best step to 1e-6 of
// each row (measured 9e-8 … 2e-7: λ carries the round-off of Newton's last solve, over δ).
TEST(CutForceSensor, FourBarPinLoadsAdjointEqualsDirectAndCentralDifferences) {
  const DesignProblem problem = fourBarPinLoads(true);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  const DesignGradient direct = directGradient(problem, functionals, x);
  EXPECT_GT(adjoint.constraints.block(1, 0, 2, 4).cwiseAbs().minCoeff(), 1e-2);  // every variable acts
  EXPECT_LE(test::relativeGap(adjoint.constraints, direct.constraints), 1e-9);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

// The continuous adjoint linearises the continuous motion, whose reaction Newton's multipliers meet
// only at first order in h (the pendulum's tension above): its gradient of ∫pin_x dt approaches the
// exact one at first order, the gap halving with h (measured 1.34e-3, 6.7e-4, 3.4e-4 relative).
TEST(CutForceSensor, ContinuousAdjointOfAPinLoadConvergesAtFirstOrder) {
  std::vector<double> gaps;
  for (const double step : {1e-3, 5e-4}) {
    const DesignProblem problem = fourBarPinLoads(false, step);
    const std::vector<ConstraintFunctional> functionals = transcribe(problem);
    const Eigen::VectorXd x = initialPoint(problem);
    ASSERT_EQ(functionals[2].name, "pin_x_integral");
    const Eigen::RowVectorXd exact = directGradient(problem, functionals, x).constraints.row(2).head(2);
    const Eigen::RowVectorXd continuous = continuousAdjointGradient(problem, functionals, x).constraints.row(2).head(2);
    gaps.push_back((continuous - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff());
  }
  EXPECT_LE(gaps[0], 1e-2);
  EXPECT_NEAR(gaps[0] / gaps[1], 2.0, 0.2);
}

}  // namespace
}  // namespace mbsopt
