// The direct method is the exact derivative of the discrete map, so it must agree with central
// finite differences of the same discrete map to their error, O(δ²) plus the Newton tolerance
// over δ, and with closed forms to the discretisation error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "problems/scene_file.hpp"
#include "sensitivity/direct_sensitivity.hpp"
#include "tests/oscillator_scene.hpp"

namespace mbsopt {
namespace {

constexpr double kPi = std::numbers::pi;

/// max over constraints and variables of |direct − central FD| relative to the largest entry.
double relativeGap(const DesignGradient& a, const DesignGradient& b) {
  return (a.constraints - b.constraints).cwiseAbs().maxCoeff() / b.constraints.cwiseAbs().maxCoeff();
}

// dΨ/dk of Ψ = ∫⟨x − ½⟩dt for x'' + k x = 0 (the closed form and its kink bound are derived in
// test_design_problem.cpp); the direct method differentiates the same discrete functional as the
// finite differences, so the two agree far more closely than either does with the closed form.
TEST(DirectSensitivity, OscillatorMatchesFiniteDifferencesAndTheClosedForm) {
  const DesignProblem problem =
      loadDesignProblem({"oscillator.yaml", std::string(test::kOscillator) + test::kOscillatorDesign});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient direct = directGradient(problem, functionals, x);
  const DesignGradient central = finiteDifferenceGradient(problem, functionals, x, 1e-5, true);
  EXPECT_LE(relativeGap(direct, central), 1e-6);
  const double omega = 2.0 * kPi, b = 0.5, theta = std::acos(b);
  const double F = 2.0 * (std::sin(theta) - b * theta);
  const double dpsi_dx = (-F / (omega * omega) + (1.0 - b) / omega) / (2.0 * omega) * 10.0;
  const double kink_bound = 0.5 * 1e-3 * omega * std::sin(theta) * 2.0 * kPi / (2.0 * omega * omega * omega) * 10.0;
  EXPECT_NEAR(direct.constraints(0, 0), dpsi_dx, kink_bound + 1e-4 * std::abs(dpsi_dx));
}

// An open spatial chain with a damped elbow spring: the stiffness, the damping and a mass as design
// variables; an acceleration response through the paper's ∫⟨φ⟩ and a position response through KS.
TEST(DirectSensitivity, OpenChainWithAccelerationResponseMatchesFiniteDifferences) {
  const DesignProblem problem = loadDesignProblem({"chain.yaml", R"(
settings: {step: 2.0e-3, end_time: 1.5}
gravity: [0, 0, -9.81]
elements:
  - {name: shoulder, type: revolute, parent: ground, axis: [0.2, 1, 0.1], q0: 0.8}
  - {name: elbow_point, type: offset, parent: shoulder, translation: [0, 0, -1]}
  - {name: elbow, type: revolute, parent: elbow_point, axis: [1, 0.3, 0], q0: -0.4}
bodies:
  - {name: upper, frame: shoulder, mass: 2, com: [0.05, -0.02, -0.5], Ixx: 0.2, Iyy: 0.25, Izz: 0.1}
  - {name: lower, frame: elbow, mass: 1.5, com: [0.03, 0.01, -0.4], Ixx: 0.1, Iyy: 0.12, Izz: 0.05}
forces:
  - {name: elbow_spring, type: joint_spring_damper, joint: elbow, k: 30, c: 0.7, rest: 0.25}
sensors:
  - {name: tip_acceleration, type: point, frame: elbow, point: [0, 0, -0.8], quantity: acceleration, component: x}
  - {name: elbow_angle, type: joint, joint: elbow, quantity: position}
design:
  variables:
    - {parameter: elbow_spring.k, lower: 1, upper: 100, scale: 10}
    - {parameter: elbow_spring.c, lower: 0.1, upper: 10, scale: 1}
    - {parameter: lower.mass, lower: 0.5, upper: 5, scale: 1}
  cost: {sensor: tip_acceleration, of: max_abs}
  artificial: {initial: 8, lower: 0, upper: 100}
  constraints:
    - {sensor: elbow_angle, of: max_abs, bound: 0.5}
  transcription: {measure: ks, rho: 20}
)"});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient direct = directGradient(problem, functionals, x);
  const DesignGradient central = finiteDifferenceGradient(problem, functionals, x, 1e-5, true);
  EXPECT_LE(relativeGap(direct, central), 1e-6) << "direct\n" << direct.constraints << "\ncentral\n"
                                                << central.constraints;
}

TEST(DirectSensitivity, RefusesClosedLoopsForNow) {
  const DesignProblem problem =
      loadDesignProblem(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml"));
  EXPECT_THROW(directGradient(problem, transcribe(problem), initialPoint(problem)), std::invalid_argument);
}

}  // namespace
}  // namespace mbsopt
