// Scenes shared by the sensitivity tests.
#pragma once

namespace mbsopt::test {

// A unit mass on a spring of stiffness (2π)² N/m released from x = 1 m: one period per second.
inline constexpr const char* kOscillator = R"(settings: {step: 1.0e-3, end_time: 1}
elements:
  - {name: x, type: prismatic, parent: ground, axis: [1, 0, 0], q0: 1}
bodies:
  - {name: mass, frame: x, mass: 1, Ixx: 1, Iyy: 1, Izz: 1}
forces:
  - {name: spring, type: joint_spring_damper, joint: x, k: 39.478417604357434}
sensors:
  - {name: position, type: joint, joint: x, quantity: position}
)";

/// The same with a design problem: the spring's stiffness (scale 10), cost max x through b = 0.5,
/// transcribed as the paper's ∫⟨x − b⟩dt.
inline constexpr const char* kOscillatorDesign = R"(design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: position, of: max}
  artificial: {initial: 0.5, lower: -2, upper: 2}
  transcription: {measure: positive_part}
)";

/// An open spatial chain with a damped elbow spring: the stiffness, the damping and a mass as design
/// variables; an acceleration response as the cost, a joint angle as a constraint; KS transcription.
inline constexpr const char* kOpenChainProblem = R"(
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
)";

/// A design section for the shipped four-bar (problems/scenes/four_bar.yaml): masses and a centre of
/// mass, which the projections' metric M depends on; the paper's ⟨⟩ functionals on a position and
/// an angle, both active over the first second. Append a `transcription:` line for another measure.
inline constexpr const char* kFourBarDesign = R"(
design:
  variables:
    - {parameter: coupler_bar.mass, lower: 0.5, upper: 5}
    - {parameter: rocker_bar.com.x, lower: 0.1, upper: 0.7}
    - {parameter: crank_bar.mass, lower: 0.1, upper: 5}
  cost: {sensor: joint_c_y, of: max_abs}
  artificial: {initial: 1.0, lower: 0, upper: 2}
  constraints:
    - {sensor: coupler_angle, of: max_abs, bound: 0.5}
)";

}  // namespace mbsopt::test
