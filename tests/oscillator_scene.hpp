// A one-degree-of-freedom scene shared by the sensitivity tests.
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

/// The same with a design problem: the spring's stiffness (scale 10), cost max x through b = 0.5.
inline constexpr const char* kOscillatorDesign = R"(design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: position, of: max}
  artificial: {initial: 0.5, lower: -2, upper: 2}
)";

}  // namespace mbsopt::test
