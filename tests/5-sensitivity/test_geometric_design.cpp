// Geometric design variables: an offset's translation (NAME.translation.x, y, z) moves frames, so
// the kinematics, the loop closure b(q; b) and the sensors depend on it directly. The exact methods
// carry ∂b/∂b, ∂ḃ/∂b and ∂b̈/∂b in the closure rows, the sensors' explicit ∂y/∂b, and the initial
// state that a design closes again on its loops (5-sensitivity/initial_state.hpp). Checked against
// central differences of the simulation, against each other, and on a sensor whose derivative is
// known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/algorithms/tangent.hpp"
#include "mbsopt/sensitivity/continuous_adjoint.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"
#include "mbsopt/sensitivity/initial_state.hpp"
#include "mbsopt/sensitivity/response_jacobian.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/gradient_checks.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

using test::relativeGap;

SceneSource shippedScene(const std::string& name) {
  return readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml");
}

/// The four-bar swinging under gravity for 1 s with `variables` as the design (a YAML list): the
/// cost on the crank's acceleration (active), a position's extreme, an integral and a final value.
DesignProblem fourBarDesign(SceneSource source, const std::string& variables, double step = 1e-3) {
  source.text += R"(  - {name: crank_rate, type: joint, joint: crank, quantity: velocity}
  - {name: crank_acc, type: joint, joint: crank, quantity: acceleration}
design:
  variables:
)" + variables + R"(  cost: {sensor: crank_acc, of: max_abs}
  artificial: {initial: 5, lower: 0, upper: 200}
  constraints:
    - {sensor: joint_c_y, of: max_abs, bound: 0.7}
    - {sensor: crank_rate, of: integral, bound: -1}
    - {sensor: joint_c_x, of: final, bound: 0.9}
  transcription: {measure: positive_part}
)";
  return loadDesignProblem(source, {{"settings.end_time", 1.0}, {"settings.step", step}});
}

/// Its three link lengths, the coupler's end off its axis and a mass.
DesignProblem fourBarLengths(double step = 1e-3) {
  return fourBarDesign(shippedScene("four_bar"),
                       "    - {parameter: crank_tip.translation.x, lower: 0.3, upper: 0.5}\n"
                       "    - {parameter: rocker_pivot.translation.x, lower: 0.9, upper: 1.1}\n"
                       "    - {parameter: rocker_tip.translation.x, lower: 0.7, upper: 0.9}\n"
                       "    - {parameter: coupler_tip.translation.y, lower: -0.1, upper: 0.1}\n"
                       "    - {parameter: coupler_bar.mass, lower: 1, upper: 3}\n",
                       step);
}

TEST(GeometricDesign, AnOffsetsTranslationIsAParameterThatMovesItsFrame) {
  Model model = loadScene(shippedScene("four_bar")).scene.model;
  EXPECT_EQ(model.parameter("crank_tip.translation.x"), 0.4);
  EXPECT_EQ(model.parameter("rocker_pivot.translation.y"), 0.0);
  model.setParameter("crank_tip.translation.x", 0.45);
  model.setParameter("rocker_pivot.translation.y", 0.1);
  Workspace<double> ws(model);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.coordinateCount());
  frameGeometry(model, ws, q);
  EXPECT_EQ(ws.position[static_cast<std::size_t>(model.frame("crank_tip"))], Eigen::Vector3d(0.45, 0.0, 0.0));
  EXPECT_EQ(ws.position[static_cast<std::size_t>(model.frame("rocker_pivot"))], Eigen::Vector3d(1.0, 0.1, 0.0));
  EXPECT_THROW(model.setParameter("crank_tip.translation.z", std::nan("")), std::invalid_argument);
}

// The initial state of a design that opens the loop: closed again (b = 0, ḃ = 0 to the assembly's
// tolerance), moved only along the scene's V₁ (its V₂ components, the scene's degrees of freedom,
// stay those the user gave), and at the scene's own parameters the scene's state to the bit.
TEST(GeometricDesign, AnOpenedLoopIsClosedAgainAlongTheScenesConstrainedDirections) {
  const Scene scene = loadScene(shippedScene("four_bar")).scene;
  Eigen::VectorXd q, v;
  designInitialState(scene, scene.model, q, v);
  EXPECT_TRUE(q.cwiseEqual(scene.q0).all());
  EXPECT_TRUE(v.cwiseEqual(scene.v0).all());

  Model model = scene.model;
  model.setParameter("crank_tip.translation.x", 0.45);
  model.setParameter("rocker_tip.translation.x", 0.75);
  designInitialState(scene, model, q, v);
  Workspace<double> ws(model);
  Eigen::VectorXd b;
  Eigen::MatrixXd B;
  constraintJacobian(model, ws, q, model.freeCoordinates(), b, B);
  EXPECT_LE(b.cwiseAbs().maxCoeff(), 1e-12);
  frameRates(model, ws, v, v, KinematicsLevel::Velocity);
  closureEquations(model, ws, Derivative::Velocity, b);
  EXPECT_LE(b.cwiseAbs().maxCoeff(), 1e-12);
  Workspace<double> scene_ws(scene.model);
  Eigen::MatrixXd B_scene;
  constraintJacobian(scene.model, scene_ws, scene.q0, scene.model.freeCoordinates(), b, B_scene);
  SvdPartition partition(scene.settings.svd_threshold);
  partition.setConstraintJacobian(B_scene);
  const Eigen::VectorXd moved = q - scene.q0;  // every coordinate of the four-bar is free
  EXPECT_GT(moved.norm(), 1e-2);
  EXPECT_LE((partition.freeDirections().transpose() * moved).norm(), 1e-14 * moved.norm());
  EXPECT_LE((partition.freeDirections().transpose() * (v - scene.v0)).norm(), 1e-14);
}

// A design whose loop cannot close (a rocker too short to reach the coupler) is an error that names
// the cut joint, not a simulation that starts off the loop.
TEST(GeometricDesign, ALoopThatCannotCloseAtADesignIsNamed) {
  const Scene scene = loadScene(shippedScene("four_bar")).scene;
  Model model = scene.model;
  model.setParameter("rocker_tip.translation.x", 0.1);  // 0.4 + 0.1 + 1 … the bars cannot meet at crank 0
  model.setParameter("coupler_tip.translation.x", 0.3);
  Eigen::VectorXd q, v;
  try {
    designInitialState(scene, model, q, v);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("at this design the loop(s) closed by loop cannot be assembled"), std::string::npos)
        << e.what();
  }
}

// A dynamic closed loop: the lengths enter B, the closure's rates, M and Bᵀλ (the projections' P), and
// the initial state. Adjoint = direct to round-off; both = central differences at the best step to
// 1e-6 of each row (measured 4e-10 … 2e-8, the simulation's Newton tolerance over the step).
TEST(GeometricDesign, FourBarLengthsAdjointEqualsDirectAndCentralDifferences) {
  const DesignProblem problem = fourBarLengths();
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient direct = directGradient(problem, functionals, x);
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  for (Eigen::Index i = 0; i < 4; ++i) EXPECT_GT(direct.constraints.col(i).cwiseAbs().maxCoeff(), 1e-2) << i;
  EXPECT_LE(relativeGap(adjoint.constraints, direct.constraints), 1e-12);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
  // At a design where every length differs from the scene's, the initial state is closed again.
  Eigen::VectorXd moved = x;
  moved.head(4) << 0.45, 1.05, 0.75, 0.04;
  const DesignGradient at_moved = adjointGradient(problem, functionals, moved);
  EXPECT_LE(relativeGap(directGradient(problem, functionals, moved).constraints, at_moved.constraints), 1e-12);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, moved, at_moved, 1e-6);
}

// A kinematic loop driven in time (no degree of freedom left): the slider's acceleration, a cost
// below its peak so that it is active, depends on the crank's and the rod's lengths and the rail's
// height through the closure alone, ∂b̈/∂b included.
TEST(GeometricDesign, SliderCrankAccelerationsMatchCentralDifferences) {
  SceneSource source = shippedScene("slider_crank");
  source.text += R"(design:
  variables:
    - {parameter: crank_pin.translation.x, lower: 0.05, upper: 0.15}
    - {parameter: conrod_end.translation.x, lower: 0.3, upper: 0.6}
    - {parameter: rail.translation.y, lower: 0.0, upper: 0.1}
  cost: {sensor: slider_a, of: max_abs}
  artificial: {initial: 5, lower: 0, upper: 200}
  constraints:
    - {sensor: rod_angle, of: max_abs, bound: 0.15}
)";
  const DesignProblem problem = loadDesignProblem(source);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  EXPECT_GT(adjoint.constraints.leftCols(3).cwiseAbs().maxCoeff(), 1.0);
  EXPECT_LE(relativeGap(directGradient(problem, functionals, x).constraints, adjoint.constraints), 1e-12);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

// An open spatial chain with the elbow's offset as the design: all three methods, the continuous
// adjoint included (no loop), against central differences.
TEST(GeometricDesign, OpenChainOffsetMatchesCentralDifferencesByEveryMethod) {
  std::string text = test::kOpenChainProblem;
  const std::string variables = "    - {parameter: elbow_spring.k, lower: 1, upper: 100, scale: 10}\n";
  text.replace(text.find(variables), variables.size(),
               "    - {parameter: elbow_point.translation.z, lower: -1.5, upper: -0.5}\n"
               "    - {parameter: elbow_point.translation.x, lower: -0.3, upper: 0.3}\n");
  const DesignProblem problem = loadDesignProblem({"chain.yaml", text});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  EXPECT_GT(adjoint.constraints.leftCols(2).cwiseAbs().maxCoeff(), 1e-2);
  EXPECT_LE(relativeGap(directGradient(problem, functionals, x).constraints, adjoint.constraints), 1e-12);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
  // The continuous adjoint discretises the continuous equations: its own O(h²) error (h = 2 ms).
  EXPECT_LE(relativeGap(continuousAdjointGradient(problem, functionals, x).constraints, adjoint.constraints), 1e-2);
}

// A sensor on a frame fixed to the ground by an offset reads the offset's value and nothing of the
// state: d(final x)/d(translation.x) = 1 exactly, from the explicit ∂y/∂b alone.
TEST(GeometricDesign, ASensorOnAMovedFrameHasTheExplicitDerivative) {
  SceneSource source = shippedScene("pendulum");
  const std::string elements = "elements:\n";
  source.text.replace(source.text.find(elements), elements.size(),
                      elements + "  - {name: marker, type: offset, parent: ground, translation: [0.3, 0.2, 0]}\n");
  source.text += R"(  - {name: marker_x, type: point, frame: marker, point: [0, 0, 0], quantity: position, component: x}
design:
  variables: [{parameter: marker.translation.x, lower: 0, upper: 1}]
  cost: {sensor: angle, of: max_abs}
  artificial: {initial: 2, lower: 0, upper: 4}
  constraints: [{sensor: marker_x, of: final, bound: 0.5}]
)";
  const DesignProblem problem = loadDesignProblem(source, {{"settings.end_time", 0.5}});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const Eigen::Index row = functionals.size() - 1;
  EXPECT_EQ(directGradient(problem, functionals, x).constraints(row, 0), 1.0);
  EXPECT_EQ(adjointGradient(problem, functionals, x).constraints(row, 0), 1.0);
  EXPECT_EQ(continuousAdjointGradient(problem, functionals, x).constraints(row, 0), 1.0);
}

// A driven joint's motion is a design variable: the press's crank speed ω and initial angle φ
// (crank.motion.polynomial.1 and .0), beside the crank radius. They move the driven coordinate and
// its rates at every time point (seeded in the AD passes, seedDrivenMotions) and, through φ, the
// loop's closure at t₀ (the initial state is closed again). Adjoint = direct to round-off, central
// differences at the best step to 1e-6 (measured 4e-12 … 1e-10). The press has no degree of freedom,
// so the ram's final position is the closure's at θ = ωτ + φ: d/dω = τ d/dφ exactly.
TEST(GeometricDesign, ADrivenJointsMotionIsADesignVariable) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/suite/press_slider_crank.yaml");
  const std::string rail = "    - {parameter: rail.translation.y, lower: 0, upper: 0.2, scale: 0.1}\n";
  source.text.replace(source.text.find(rail), rail.size(),
                      "    - {parameter: crank.motion.polynomial.1, lower: 3, upper: 9}\n"
                      "    - {parameter: crank.motion.polynomial.0, lower: -0.5, upper: 0.5}\n");
  const DesignProblem problem = loadDesignProblem(source);
  EXPECT_TRUE(designMovesLoopClosure(problem));
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  Eigen::VectorXd x = initialPoint(problem);
  x[2] = 0.1;  // φ: the crank starts turned, the scene's loop opened
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  EXPECT_LE(relativeGap(directGradient(problem, functionals, x).constraints, adjoint.constraints), 1e-12);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
  const Eigen::Index final_row = static_cast<Eigen::Index>(functionals.size()) - 1;
  ASSERT_EQ(functionals.back().name, "slider_x_final");
  const double d_omega = adjoint.constraints(final_row, 1), d_phi = adjoint.constraints(final_row, 2);
  EXPECT_GT(std::abs(d_phi), 1e-3);
  EXPECT_NEAR(d_omega, 0.5 * d_phi, 1e-10 * std::abs(d_phi));  // τ = 0.5 s
}

// An offset's rotation angle turns the frames after it: a point one unit along x beyond an offset
// turned by θ sits at (cos θ, sin θ, 0) about z (the planar recursions) and at (cos θ, 0, −sin θ)
// about y (the spatial ones), at any state of the hinge behind it. So ∂y/∂θ is (−sin θ, cos θ, 0)
// and (−sin θ, 0, −cos θ) exactly, from the explicit term alone; setting the angle moves the point.
TEST(GeometricDesign, AnOffsetsRotationAngleTurnsTheFramesAfterIt) {
  for (const bool about_z : {true, false}) {
    SCOPED_TRACE(about_z ? "about z" : "about y");
    Model model;
    const Eigen::Vector3d axis = about_z ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    const FrameIndex bend = model.addOffset("bend", Model::ground, Eigen::Vector3d::Zero(), 2.0 * axis, 0.3);
    const FrameIndex tip = model.addOffset("arm", bend, Eigen::Vector3d::UnitX());
    const FrameIndex hinge = model.addRevolute("hinge", tip, axis);
    model.addBody("bob", hinge, 1.0, Eigen::Vector3d(0.5, 0.0, 0.0), 0.1 * Eigen::Matrix3d::Identity());
    for (int c = 0; c < 3; ++c)
      model.addSensor(std::string("tip_") + "xyz"[c], PointSensor{tip, Eigen::Vector3d::Zero(), Derivative::Position,
                                                                   Model::ground, c});
    EXPECT_EQ(model.planar(), about_z);
    const ParameterIndex angle = model.parameterIndex("bend.rotation.angle");
    EXPECT_TRUE(isGeometricParameter(model, angle));
    const auto expected = [&](double theta) {
      return about_z ? Eigen::Vector3d(std::cos(theta), std::sin(theta), 0.0)
                     : Eigen::Vector3d(std::cos(theta), 0.0, -std::sin(theta));
    };
    const auto slope = [&](double theta) {
      return about_z ? Eigen::Vector3d(-std::sin(theta), std::cos(theta), 0.0)
                     : Eigen::Vector3d(-std::sin(theta), 0.0, -std::cos(theta));
    };
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 0.4), v = Eigen::VectorXd::Constant(1, -0.7);
    const Eigen::VectorXd a = Eigen::VectorXd::Constant(1, 1.3);
    for (const double theta : {0.3, -1.1}) {
      model.setParameter(angle, theta);
      Workspace<AdScalar> ws(model);
      std::vector<const Sensor*> sensors;
      for (const Sensor& sensor : model.sensors()) sensors.push_back(&sensor);
      std::vector<ResponseJacobian> J;
      responseJacobians(model, ws, sensors, q, v, a, allCoordinates(model), J, {angle});
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(J[static_cast<std::size_t>(c)].value, expected(theta)[c], 1e-15) << c;
        EXPECT_NEAR(J[static_cast<std::size_t>(c)].parameters[0], slope(theta)[c], 1e-15) << c;
      }
    }
  }
}

// A bend in the crank (its tip turned by φ about z, the coupler's hinge with it) moves the four-bar's
// loop: adjoint = direct to round-off, and central differences at the best step to 1e-6, at the
// scene's straight crank and at a bend that opens the scene's loop (closed again by the design's
// initial state).
TEST(GeometricDesign, ABendInAFourBarsCrankMatchesCentralDifferences) {
  SceneSource source = shippedScene("four_bar");
  const std::string straight = "translation: [0.4, 0, 0]}";
  source.text.replace(source.text.find(straight), straight.size(),
                      "translation: [0.4, 0, 0], rotation: {axis: [0, 0, 1], angle: 0}}");
  const DesignProblem problem = fourBarDesign(source,
                                              "    - {parameter: crank_tip.rotation.angle, lower: -0.3, upper: 0.3}\n"
                                              "    - {parameter: coupler_bar.mass, lower: 1, upper: 3}\n");
  EXPECT_TRUE(designMovesLoopClosure(problem));
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  for (const double bend : {0.0, 0.1}) {
    SCOPED_TRACE(bend);
    Eigen::VectorXd x = initialPoint(problem);
    x[0] = bend;
    const DesignGradient adjoint = adjointGradient(problem, functionals, x);
    EXPECT_LE(relativeGap(directGradient(problem, functionals, x).constraints, adjoint.constraints), 1e-12);
    EXPECT_GT(adjoint.constraints.col(0).cwiseAbs().maxCoeff(), 1e-2);
    test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
  }
}

// A track's numbers as design variables of the tram, whose rear bogie closes the loop on the track:
// the arc's radius and the first straight's length move both sliders and the closure (∂b/∂b), the
// guidance's heading ψ(s) and the curvature bias κ ṡ². Four seconds take both bogies into the arc;
// the bounds of 0.2° on the yaw angles and an artificial variable of 0.3 m/s² make every measure
// active, so each row has entries in the track's columns. Adjoint = direct to round-off; central
// differences at the best step to 1e-6 of each row's largest design entry.
TEST(GeometricDesign, ATracksNumbersAreDesignVariablesOfTheTramsLoop) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = source.text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    source.text.replace(at, from.size(), to);
  };
  replace("    - {parameter: front_secondary.k, lower: 50e3, upper: 1000e3, scale: 100e3}\n",
          "    - {parameter: rail.segments.1.radius, lower: 10, upper: 20, scale: 10}\n"
          "    - {parameter: rail.segments.0.length, lower: 11, upper: 13}\n"
          "    - {parameter: front_secondary.k, lower: 50e3, upper: 1000e3, scale: 100e3}\n");
  replace("artificial: {initial: 3,", "artificial: {initial: 0.3,");
  for (int i = 0; i < 2; ++i) replace("bound: 10 deg", "bound: 0.2 deg");
  const DesignProblem problem = loadDesignProblem(source, {{"settings.end_time", 4.0}});
  EXPECT_TRUE(designMovesLoopClosure(problem));
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = adjointGradient(problem, functionals, x);
  EXPECT_LE(relativeGap(directGradient(problem, functionals, x).constraints, adjoint.constraints), 1e-12);
  EXPECT_GT(adjoint.constraints.col(0).cwiseAbs().maxCoeff(), 1e-2);  // the radius acts on every row
  EXPECT_GT(adjoint.constraints.col(1).cwiseAbs().maxCoeff(), 1e-2);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

// The continuous adjoint with variables that move the loop: its equations then carry B s = −∂b/∂b,
// whose multiplier adds ∫νᵀ ∂b/∂b dt, the closure's b̈ in the acceleration responses (−b̄ ∂b̈/∂b),
// and the initial state's S_q₀, S_v₀ (−p(0)ᵀS_q₀ − w(0)ᵀM S_v₀). It discretises the continuous
// equations, so it meets the exact gradient of the discrete functionals at second order in h: the
// gap quarters when h halves (measured 5.0e-5 → 1.3e-5 → 3.2e-6 of the largest entry), the lengths'
// columns and the mass's alike. A final value converges at first order only, in every column (its
// terminal seed is a trapezoidal end weight), so its row is left out. Without any of the three terms
// the gap does not shrink.
TEST(GeometricDesign, TheContinuousAdjointOfALoopsLengthsConvergesAtSecondOrder) {
  std::vector<double> gaps;
  for (const double step : {1e-3, 5e-4}) {
    const DesignProblem problem = fourBarLengths(step);
    const std::vector<ConstraintFunctional> functionals = transcribe(problem);
    ASSERT_EQ(functionals.back().name, "joint_c_x_final");
    const Eigen::VectorXd x = initialPoint(problem);
    const auto rows = static_cast<Eigen::Index>(functionals.size()) - 1;
    const Eigen::MatrixXd exact = directGradient(problem, functionals, x).constraints.topLeftCorner(rows, 5);
    const Eigen::MatrixXd continuous =
        continuousAdjointGradient(problem, functionals, x).constraints.topLeftCorner(rows, 5);
    gaps.push_back(relativeGap(continuous, exact));
  }
  EXPECT_LE(gaps[0], 1e-3);
  EXPECT_NEAR(gaps[0] / gaps[1], 4.0, 0.8) << gaps[0] << " " << gaps[1];
}

}  // namespace
}  // namespace mbsopt
