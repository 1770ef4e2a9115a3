// M(q) factored by the articulated-body recursion (3-algorithms/articulated_body.hpp) in the Newmark
// step. Runs with the recursion and the range-space solves (NewmarkSettings::articulated_mass_from)
// against the same runs with the CRBA M and the LU of V₂ᵀMV₂: the two solve the same equations (the
// augmented Newton system (41) and the projections) at every step, each to Newton's tolerance, so
// their trajectories may differ only by what that tolerance lets through: per step, q̈ by
// tol·(1 + ‖q̈‖∞) or the increments' round-off floor, whichever is larger (ε times the loop's reach
// over βh², incrementRoundoffFloor in newmark.cpp); q by βh² times that, summed over the steps. The
// bounds below take ten times those (two runs, each off by up to its bound, and what the differences
// of the earlier steps carry into the later ones). Measured: |Δq̈| 1.9e-9, 3.0e-8, 9.3e-8 against
// bounds of 1.5e-7, 1.8e-7, 3.4e-7 for 8, 24, 64 links; |Δq| 6e-14 … 2e-12 rad.
// And a coordinate that moves no inertia: the factorization declines it, and the step falls back
// to the dense path, which the loop keeps regular.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "mbsopt/algorithms/articulated_body.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/design/chain_scenes.hpp"

namespace mbsopt {
namespace {

Trajectory simulate(Scene scene, bool recursive) {
  scene.settings.articulated_mass_from = recursive ? 0 : std::numeric_limits<int>::max();
  NewmarkIntegrator integrator(scene.model, scene.settings);
  return integrator.simulate(scene.q0, scene.v0);
}

TEST(ArticulatedMass, ClosedChainRunsEqualTheDenseRuns) {
  for (const int links : {8, 24, 64}) {
    Scene scene = closedPlanarChainScene(links);
    scene.settings.end_time = 0.3;
    const Trajectory dense = simulate(scene, false), recursive = simulate(scene, true);
    ASSERT_EQ(dense.q.rows(), recursive.q.rows());
    const NewmarkSettings& s = scene.settings;
    const double beta_h2 = s.beta * s.step * s.step;
    const double reach = 0.5 * links;  // m, the links end to end
    const double per_step = s.newton_tolerance * (1.0 + dense.a.cwiseAbs().maxCoeff()) +
                            std::numeric_limits<double>::epsilon() * reach / beta_h2;
    const double steps = static_cast<double>(dense.statistics.steps);
    EXPECT_LE((dense.a - recursive.a).cwiseAbs().maxCoeff(), 10.0 * per_step) << links << " links";
    EXPECT_LE((dense.q - recursive.q).cwiseAbs().maxCoeff(), 10.0 * steps * beta_h2 * per_step) << links << " links";
    EXPECT_LE((dense.v - recursive.v).cwiseAbs().maxCoeff(), 10.0 * steps * s.gamma * s.step * per_step) << links << " links";
  }
}

TEST(ArticulatedBodyFactorization, DeclinesACoordinateThatMovesNoInertia) {
  // A prismatic joint with nothing beyond it: its row and column of M are zero. With a body beyond
  // it whose mass is all that resists it, the same model factors.
  for (const bool loaded : {false, true}) {
    Model model;
    const FrameIndex arm = model.addRevolute("hinge", Model::ground, Eigen::Vector3d::UnitZ());
    model.addBody("arm", arm, 2.0, Eigen::Vector3d(0.5, 0.0, 0.0), Eigen::Matrix3d::Identity() * 0.1);
    const FrameIndex slider = model.addPrismatic("slider", model.addOffset("tip", arm, Eigen::Vector3d(1.0, 0.0, 0.0)),
                                                 Eigen::Vector3d::UnitX());
    if (loaded) model.addBody("bead", slider, 1e-3, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 1e-6);
    Workspace<double> ws(model);
    const Eigen::VectorXd q = Eigen::Vector2d(0.3, 0.1), zero = Eigen::VectorXd::Zero(2);
    forwardKinematics(model, ws, q, zero, zero, KinematicsLevel::Velocity);
    ArticulatedBodyFactorization factorization;
    EXPECT_EQ(factorization.factor(model, ws, {0, 1}), loaded) << (loaded ? "with" : "without") << " the bead";
  }
}

/// The closed chain of `links` links with a massless prismatic joint along the last link, between
/// it and the pin: that coordinate moves no inertia (a zero row and column of M), but the loop holds
/// it, so M is singular and V₂ᵀMV₂ is not.
Scene chainWithMasslessSlide(int links) {
  Scene scene = planarChainScene(links);
  Model& m = scene.model;
  const FrameIndex slide = m.addPrismatic("slide", m.frame("tip" + std::to_string(links - 1)), Eigen::Vector3d::UnitX());
  scene.q0 = Eigen::VectorXd::Constant(m.coordinateCount(), 2.0 / links);
  scene.q0[m.coordinate("slide")] = 0.0;
  scene.v0 = Eigen::VectorXd::Zero(m.coordinateCount());
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  double heading = 0.0;
  for (int i = 0; i < links; ++i) {
    heading += scene.q0[i];
    tip += 0.5 * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0);
  }
  m.addSphericalCut("pin", m.addOffset("anchor", Model::ground, tip), slide);
  return scene;
}

TEST(ArticulatedMass, AJointThatMovesNoInertiaTakesTheDensePath) {
  Scene scene = chainWithMasslessSlide(24);
  scene.settings.end_time = 0.2;
  const Model& model = scene.model;
  Workspace<double> ws(model);
  forwardKinematics(model, ws, scene.q0, scene.v0, scene.v0, KinematicsLevel::Velocity);
  ASSERT_FALSE(ArticulatedBodyFactorization().factor(model, ws, model.freeCoordinates()));
  // 25 free coordinates: the defaults try the recursion at every step, it declines, and the step
  // takes the dense path, the very arithmetic of a run that never tries it.
  ASSERT_GE(static_cast<int>(model.freeCoordinates().size()), scene.settings.articulated_mass_from);
  NewmarkIntegrator defaults(model, scene.settings);
  const Trajectory tried = defaults.simulate(scene.q0, scene.v0);
  const Trajectory dense = simulate(scene, false);
  EXPECT_EQ((tried.q - dense.q).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((tried.a - dense.a).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE(dense.statistics.max_closure_error, 1e-9);
}

}  // namespace
}  // namespace mbsopt
