// The stepping contract of NewmarkIntegrator (newmark.hpp), as Drake's DoStep: attemptStep says how
// the step came out, and any outcome but Converged leaves the integrator exactly as it was, so that a
// step controller may try again with another step; acceptStep reports the checks' outcome.
#include <gtest/gtest.h>

#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {
namespace {

// A pendulum thrown fast through large angles, with Newton allowed 4 iterations: a step of 0.5 s
// (a quarter turn at 20 rad/s and more) is beyond it, one of 1 ms is not.
struct FastPendulum {
  Model model;
  NewmarkSettings settings;
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(1), v0 = Eigen::VectorXd::Constant(1, 20.0);
  FastPendulum() {
    const FrameIndex hinge = model.addRevolute("hinge", Model::ground, Eigen::Vector3d::UnitZ());
    model.addBody("bob", hinge, 1.0, Eigen::Vector3d::UnitX(), 1e-2 * Eigen::Matrix3d::Identity());
    model.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
    settings.end_time = 1.0;
    settings.max_newton_iterations = 4;
  }
};

TEST(StepOutcomes, AFailedAttemptLeavesTheIntegratorAsItWasAndSaysWhy) {
  const FastPendulum p;
  NewmarkIntegrator integrator(p.model, p.settings);
  integrator.initialize(p.q0, p.v0);
  ASSERT_TRUE(integrator.attemptStep(1e-3).converged());
  ASSERT_TRUE(integrator.acceptStep().converged());
  const Eigen::VectorXd q = integrator.q(), v = integrator.v(), a = integrator.a();
  const double t = integrator.time();
  const long steps = integrator.stepCount();

  const StepOutcome failed = integrator.attemptStep(t + 0.5);
  EXPECT_EQ(failed.status, StepStatus::NewtonDiverged) << toString(failed.status) << ": " << failed.reason;
  EXPECT_TRUE(smallerStepMayHelp(failed.status));
  EXPECT_NE(failed.reason.find("did not converge"), std::string::npos) << failed.reason;
  EXPECT_EQ(failed.element, "hinge");
  EXPECT_DOUBLE_EQ(failed.time, t + 0.5);
  // As it was, to the bit.
  EXPECT_EQ(integrator.time(), t);
  EXPECT_EQ(integrator.stepCount(), steps);
  EXPECT_EQ(integrator.q(), q);
  EXPECT_EQ(integrator.v(), v);
  EXPECT_EQ(integrator.a(), a);

  // And it goes on from there as if the attempt had not been made: the same step as a second
  // integrator that never tried the long one.
  NewmarkIntegrator untried(p.model, p.settings);
  untried.initialize(p.q0, p.v0);
  ASSERT_TRUE(untried.attemptStep(1e-3).converged());
  ASSERT_TRUE(untried.acceptStep().converged());
  ASSERT_TRUE(integrator.attemptStep(t + 1e-3).converged());
  ASSERT_TRUE(untried.attemptStep(t + 1e-3).converged());
  ASSERT_TRUE(integrator.acceptStep().converged());
  ASSERT_TRUE(untried.acceptStep().converged());
  EXPECT_NEAR(integrator.q()[0], untried.q()[0], 1e-12);
}

TEST(StepOutcomes, AFixedStepRunThrowsTheOutcomeOfItsFailedStep) {
  FastPendulum p;
  p.settings.step = 0.5;
  try {
    NewmarkIntegrator(p.model, p.settings).simulate(p.q0, p.v0);
    FAIL() << "a step Newton cannot take went through";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.status, StepStatus::NewtonDiverged);
    EXPECT_EQ(e.outcome().element, "hinge");
    EXPECT_EQ(e.step, 1);
  }
}

}  // namespace
}  // namespace mbsopt
