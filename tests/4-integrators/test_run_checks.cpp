// The Newton convergence test at every scale (4-integrators/newton_convergence.hpp) and the checks every
// step passes (4-integrators/run_checks.hpp).
//
// Scale invariance: the four-bar of problems/scenes/four_bar.yaml written in millimetres (lengths ×1e3,
// inertias ×1e6, gravity ×1e3), and placed 1 km from the origin, is the same mechanism: its joint
// angles are dimensionless and must follow the same trajectory. The Newton iterations stop at the
// round-off of each version's own equations, so the trajectories agree to round-off amplified over
// the run (bounded here by 1e-7 rad, far below the 1e-4 rad the Newmark error is at h = 1 ms), and
// every version must complete.
//
// One factorization per step: with the loops closed at position level every step factors M(qₙ₊₁)
// for its projections, and Newton's next iterations reuse it (J = M) until their contraction asks
// for the tangent part; every factorization then follows a change of the matrix (a step's M, or a
// refresh of M or of the AD tangents inside Newton), none is repeated for Newton. On a long chain this
// also needs the round-off test to allow for rows that sum hundreds of terms.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <sstream>
#include <string>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/integrators/run_checks.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/chain_scenes.hpp"
#include "mbsopt/design/tramway.hpp"

namespace mbsopt {
namespace {

/// The four-bar with every length multiplied by `unit` (1: metres, 1e3: millimetres) and its ground
/// pivots moved by `offset` metres along x and y.
std::string fourBar(double unit, double offset, const std::string& settings) {
  std::ostringstream s;
  s.precision(17);
  const double L = unit, I = unit * unit;
  s << "settings: {" << settings << "}\n"
    << "gravity: [0, " << -9.81 * L << ", 0]\n"
    << "elements:\n"
    << "  - {name: base, type: offset, parent: ground, translation: [" << offset * L << ", " << offset * L << ", 0]}\n"
    << "  - {name: crank, type: revolute, parent: base, axis: [0, 0, 1], q0: 0}\n"
    << "  - {name: crank_tip, type: offset, parent: crank, translation: [" << 0.4 * L << ", 0, 0]}\n"
    << "  - {name: coupler, type: revolute, parent: crank_tip, axis: [0, 0, 1], q0: 0.92729521800161223}\n"
    << "  - {name: coupler_tip, type: offset, parent: coupler, translation: [" << 1.0 * L << ", 0, 0]}\n"
    << "  - {name: rocker_pivot, type: offset, parent: base, translation: [" << 1.0 * L << ", 0, 0]}\n"
    << "  - {name: rocker, type: revolute, parent: rocker_pivot, axis: [0, 0, 1], q0: 90 deg}\n"
    << "  - {name: rocker_tip, type: offset, parent: rocker, translation: [" << 0.8 * L << ", 0, 0]}\n"
    << "bodies:\n"
    << "  - {name: crank_bar, frame: crank, mass: 0.8, com: [" << 0.2 * L << ", 0, 0], Ixx: " << 0.0001 * I
    << ", Iyy: " << 0.0107 * I << ", Izz: " << 0.0107 * I << "}\n"
    << "  - {name: coupler_bar, frame: coupler, mass: 2.0, com: [" << 0.5 * L << ", 0, 0], Ixx: " << 0.0003 * I
    << ", Iyy: " << 0.167 * I << ", Izz: " << 0.167 * I << "}\n"
    << "  - {name: rocker_bar, frame: rocker, mass: 1.6, com: [" << 0.4 * L << ", 0, 0], Ixx: " << 0.0003 * I
    << ", Iyy: " << 0.0853 * I << ", Izz: " << 0.0853 * I << "}\n"
    << "cuts:\n"
    << "  - {name: loop, type: revolute, frame_a: coupler_tip, frame_b: rocker_tip, axis_in_a: [0, 0, 1], "
       "axis_in_b: [0, 0, 1]}\n";
  return s.str();
}

Trajectory simulate(const std::string& text) {
  LoadedScene loaded = loadScene({"inline.yaml", text});
  return NewmarkIntegrator(loaded.scene.model, loaded.scene.settings).simulate(loaded.scene.q0, loaded.scene.v0);
}

TEST(NewtonConvergence, TheSameMechanismInOtherUnitsAndFarFromTheOriginFollowsTheSameAngles) {
  const std::string settings = "step: 1.0e-3, end_time: 1.0";
  const Trajectory metres = simulate(fourBar(1.0, 0.0, settings));
  for (const auto& [unit, offset] : {std::pair{1e3, 0.0}, std::pair{1.0, 1e3}, std::pair{1e3, 1e3}}) {
    Trajectory other;
    ASSERT_NO_THROW(other = simulate(fourBar(unit, offset, settings))) << "unit " << unit << ", offset " << offset;
    ASSERT_EQ(other.q.cols(), metres.q.cols());
    EXPECT_LE((other.q - metres.q).cwiseAbs().maxCoeff(), 1e-7) << "unit " << unit << ", offset " << offset;
    // The last Newton residual of each step, each row over the magnitude of its terms: the iteration
    // stopped at round-off or at the increment tolerance 1e-10, never far from a solution.
    EXPECT_LT(other.statistics.max_relative_residual, 1e-6);
  }
}

TEST(NewtonConvergence, NewtonReusesTheProjectionsFactorizationOfEachStep) {
  const auto expectOneFactorizationPerChange = [](const Scene& scene, const std::string& name) {
    const Trajectory run = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
    const IntegratorStatistics& s = run.statistics;
    ASSERT_GT(s.steps, 100) << name;
    EXPECT_EQ(s.jacobian_updates, 1) << name << ": the AD tangents once, for the first step";
    EXPECT_GE(s.mass_updates, s.steps) << name << ": a fresh M for every step's projections";
    // The initial M, then one per change of M or of the tangents: no second one per step for J.
    EXPECT_EQ(s.factorizations, 1 + s.mass_updates + s.jacobian_updates) << name;
  };
  expectOneFactorizationPerChange(tramwayScene(), "tramway");
  expectOneFactorizationPerChange(closedPlanarChainScene(24), "closed chain of 24 links");
  // 257 frames: its joints' rows sum up to 256 rounded wrenches, and Newton's residual stalls at 70-90
  // ε·S. Held to kFactor = 64, Newton took that stall for a stale matrix and brought in the tangent
  // part at 0.235 s (for good: every later step then factored J and M, O(n³) each); with the factor
  // scaled by the frame count (NewtonRoundoff::factor) it accepts those iterates.
  expectOneFactorizationPerChange(closedPlanarChainScene(128), "closed chain of 128 links");
}

TEST(RunChecks, LoopsThatDriftPastTheClosureToleranceStopTheRunAtTheCut) {
  // The acceleration-level closure (the paper's (38)) lets positions drift by O(h²) per unit time;
  // a tolerance of 1e-12 relative to the loop's reach is below that drift, so the run must stop.
  try {
    simulate(fourBar(1.0, 0.0, "step: 1.0e-3, end_time: 1.0, closure: acceleration, closure_tolerance: 1.0e-12"));
    FAIL() << "the run completed with its loop open";
  } catch (const SimulationError& error) {
    EXPECT_EQ(error.element, "loop");
    EXPECT_NE(std::string(error.what()).find("come apart"), std::string::npos) << error.what();
    EXPECT_GT(error.time, 0.0);
  }
  // The default tolerance of the acceleration closure (1e-2) lets its drift through over this run.
  EXPECT_NO_THROW(simulate(fourBar(1.0, 0.0, "step: 1.0e-3, end_time: 1.0, closure: acceleration")));
}

/// An undamped chain of eight uniform links (0.5 m, 1 kg) released horizontal, with an optional damper.
std::string chain(double step, double damping) {
  std::ostringstream s;
  s << "settings: {step: " << step << ", end_time: 2}\ngravity: [0, -9.81, 0]\nelements:\n";
  std::string parent = "ground";
  for (int i = 0; i < 8; ++i) {
    s << "  - {name: j" << i << ", type: revolute, parent: " << parent << ", axis: [0, 0, 1]}\n"
      << "  - {name: e" << i << ", type: offset, parent: j" << i << ", translation: [0.5, 0, 0]}\n";
    parent = "e" + std::to_string(i);
  }
  s << "bodies:\n";
  for (int i = 0; i < 8; ++i)
    s << "  - {name: b" << i << ", frame: j" << i
      << ", mass: 1, com: [0.25, 0, 0], Ixx: 0, Iyy: 0.0208333333333333, Izz: 0.0208333333333333}\n";
  if (damping > 0.0) s << "forces:\n  - {name: d, type: joint_spring_damper, joint: j0, k: 0, c: " << damping << "}\n";
  return s.str();
}

TEST(RunChecks, AStepTooLargeForTheChainIsAnEnergyErrorNotAnAnswer) {
  // At h = 0.05 s the trapezoidal equations of the released chain have a spurious solution that
  // Newton finds: the energy jumps by orders of magnitude. At h = 0.01 s the run is sound.
  try {
    simulate(chain(0.05, 0.0));
    FAIL() << "the run completed";
  } catch (const SimulationError& error) {
    EXPECT_NE(std::string(error.what()).find("mechanical energy grew"), std::string::npos) << error.what();
  }
  EXPECT_NO_THROW(simulate(chain(0.01, 0.0)));
}

TEST(RunChecks, OnlyARunWhereNoForceDoesWorkIsHeldToItsEnergy) {
  EXPECT_TRUE(conservesEnergy(loadScene({"inline.yaml", chain(0.01, 0.0)}).scene.model));
  EXPECT_FALSE(conservesEnergy(loadScene({"inline.yaml", chain(0.01, 0.5)}).scene.model));
  EXPECT_TRUE(conservesEnergy(loadScene({"inline.yaml", fourBar(1.0, 0.0, "step: 1.0e-3")}).scene.model));
}

}  // namespace
}  // namespace mbsopt
