// The trapezoidal Newmark scheme at variable steps (4-integrators/adaptive_newmark, NewmarkSettings::time_grid).
//
// References from outside the code under test:
// - the oscillator x'' = −ω²x: from any state (xₙ, ẋₙ) the exact solution after h is
//   xₙ cos ωh + ẋₙ/ω sin ωh, so every step's true local error is known in closed form, and the global
//   error of a run is x − cos ωt;
// - Andrews' squeezer's published angles at t = 0.03 s.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "mbsopt/integrators/adaptive_newmark.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "tests/integrator_scenes.hpp"

namespace mbsopt {
namespace {

using test::kOmega;
using test::oscillator;
using test::sceneFile;

TEST(AdaptiveNewmark, EveryStepsTrueLocalErrorMeetsTheToleranceAndTheControllerUsesIt) {
  // (LE) is the local error to leading order, (ωh)³/12 sin φ from phase φ. Where that term vanishes
  // (sin φ = 0) the next ones are (ωh)⁴/24 cos φ in (LE) and (ωh)⁴/12 cos φ in the truth: there the true
  // local error may reach twice the tolerance, not more (10 % for the terms after). And the steps are
  // not needlessly small: the largest reaches half of it (the controller aims at 0.9³ ≈ 0.73).
  const Scene scene = oscillator(2.0);
  for (const double tolerance : {1e-6, 1e-9}) {
    LocalErrorControl control;
    control.tolerance = {tolerance, 0.0};
    const AdaptiveRun run = adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, control);
    const Trajectory& t = run.trajectory;
    double largest = 0.0;
    for (Eigen::Index k = 0; k + 1 < t.time.size(); ++k) {
      const double h = t.time[k + 1] - t.time[k];
      const double exact = t.q(0, k) * std::cos(kOmega * h) + t.v(0, k) / kOmega * std::sin(kOmega * h);
      largest = std::max(largest, std::abs(t.q(0, k + 1) - exact));
    }
    EXPECT_LT(largest, 2.2 * tolerance) << tolerance;
    EXPECT_GT(largest, 0.5 * tolerance) << tolerance;
    EXPECT_DOUBLE_EQ(t.time[t.time.size() - 1], 2.0);
  }
}

TEST(AdaptiveNewmark, ItsLocalErrorEstimateIsTheTaylorTermOfTheUpdate) {
  // One step of h from x = cos φ: (LE) = h²/12 (ẍ₁ − ẍ₀) against the true local error, whose leading
  // term is ω³h³ sin φ / 12: the ratio tends to 1 as O(ωh), checked at two steps (two-sided on the rate).
  const Scene scene = oscillator(1.0);
  const double phi = 0.7;
  Eigen::VectorXd q0(1), v0(1);
  q0 << std::cos(phi);
  v0 << -kOmega * std::sin(phi);
  std::vector<double> misfit;
  for (const double h : {1e-2, 5e-3}) {
    NewmarkIntegrator integrator(scene.model, scene.settings);
    integrator.initialize(q0, v0);
    ASSERT_TRUE(integrator.attemptStep(h).converged());
    const double estimate = localErrorNorm(scene.model, h, integrator.acceptedAcceleration(), integrator.a(),
                                           integrator.q(), {1.0, 0.0});
    const double truth = std::abs(integrator.q()[0] - std::cos(phi + kOmega * h));
    misfit.push_back(std::abs(estimate / truth - 1.0));
  }
  EXPECT_LT(misfit[0], 0.1);
  const double rate = misfit[0] / misfit[1];  // O(ωh): 2 per halving
  EXPECT_GT(rate, 1.6);
  EXPECT_LT(rate, 2.5);
}

TEST(AdaptiveNewmark, RunsDrivenByAccuracyMeetItWithinTenTimesTheirEstimate) {
  const Scene scene = oscillator(2.0);
  for (const double tolerance : {1e-3, 1e-5, 1e-7}) {
    AccuracyGoal goal;
    goal.tolerance = {tolerance, 0.0};
    const AccurateRun run = adaptiveToAccuracy(scene.model, scene.settings, scene.q0, scene.v0, goal);
    const double error = test::trueOscillatorError(run.run.trajectory), estimate = run.run.positionError();
    EXPECT_LT(error, tolerance) << tolerance;
    EXPECT_LT(error, 10.0 * estimate) << tolerance;
    EXPECT_LT(estimate, 10.0 * error) << tolerance;
    EXPECT_LE(run.weighted_error, kAcceptedFraction);
  }
}

TEST(AdaptiveNewmark, AndrewsSqueezerMeetsThePublishedAngles) {
  test::expectAndrewsMeetsThePublishedAngles("adaptive", {1e-3, 1e-5});
}

TEST(AdaptiveNewmark, StepsEndAtTheOutputTimesAndGrowAndShrinkWithTheMotion) {
  // Andrews' squeezer: the crank's acceleration rises by orders of magnitude over the 30 ms, so the
  // steps do not stay alike; every output time is a time point of the run, exactly.
  const Scene scene = sceneFile("problems/scenes/hard/andrews_squeezer.yaml");
  LocalErrorControl control;
  control.tolerance = {1e-7, 0.0};
  for (int m = 1; m < 30; ++m) control.stop_times.push_back(1e-3 * m);
  const AdaptiveRun run = adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, control);
  const Eigen::VectorXd& time = run.trajectory.time;
  ASSERT_EQ(run.stops.size(), 31u);
  EXPECT_EQ(run.stops.front(), 0);
  for (int m = 1; m < 30; ++m) EXPECT_EQ(time[run.stops[static_cast<std::size_t>(m)]], 1e-3 * m);
  EXPECT_EQ(time[run.stops.back()], 0.03);
  const Eigen::VectorXd steps = time.tail(time.size() - 1) - time.head(time.size() - 1);
  EXPECT_GT(steps.maxCoeff(), 5.0 * steps.minCoeff());
}

TEST(AdaptiveNewmark, AStepNewtonCannotSolveIsRetriedSmaller) {
  // A first step of the whole 30 ms on the squeezer: rejected (Newton or the error), the run completes.
  const Scene scene = sceneFile("problems/scenes/hard/andrews_squeezer.yaml");
  LocalErrorControl control;
  control.tolerance = {1e-5, 0.0};
  control.first_step = 0.03;
  const AdaptiveRun run = adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, control);
  EXPECT_GE(run.trajectory.statistics.rejected_steps, 1);
  EXPECT_DOUBLE_EQ(run.trajectory.time[run.trajectory.time.size() - 1], 0.03);
}

TEST(AdaptiveNewmark, RefusesASchemeWhoseLocalErrorItDoesNotKnow) {
  Scene scene = oscillator(1.0);
  scene.settings.beta = 0.3025;
  scene.settings.gamma = 0.6;
  EXPECT_THROW(adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, {}), std::invalid_argument);
}

TEST(TimeGrid, ReplaysAnAdaptiveRunAndAUniformGridIsTheFixedStep) {
  // A run on the time points of an adaptive run repeats it (to Newton's tolerance: Newton's start may
  // differ); a grid of the multiples of h is the fixed-step run (to the round-off of the times).
  const Scene scene = sceneFile("problems/scenes/four_bar.yaml");
  LocalErrorControl control;
  control.tolerance = {1e-6, 0.0};
  const AdaptiveRun adaptive = adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, control);
  NewmarkSettings replay = scene.settings;
  replay.time_grid = timeGrid(adaptive.trajectory.time);
  const Trajectory again = NewmarkIntegrator(scene.model, replay).simulate(scene.q0, scene.v0);
  ASSERT_EQ(again.time.size(), adaptive.trajectory.time.size());
  EXPECT_LT((again.q - adaptive.trajectory.q).cwiseAbs().maxCoeff(), 1e-8);

  const Trajectory fixed = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  NewmarkSettings uniform = scene.settings;
  uniform.time_grid = timeGrid(fixed.time);
  const Trajectory on_grid = NewmarkIntegrator(scene.model, uniform).simulate(scene.q0, scene.v0);
  EXPECT_LT((on_grid.q - fixed.q).cwiseAbs().maxCoeff(), 1e-11);
}

TEST(TimeGrid, AGridThatIsNotOneIsRefusedByName) {
  NewmarkSettings settings;
  settings.end_time = 1.0;
  settings.time_grid = std::make_shared<const std::vector<double>>(std::vector<double>{0.0, 0.5, 0.5, 1.0});
  EXPECT_EQ(settingsDefect(settings).field, "time_grid");
  settings.time_grid = std::make_shared<const std::vector<double>>(std::vector<double>{0.0, 0.5});
  EXPECT_EQ(settingsDefect(settings).field, "time_grid");  // ends before the end time
  settings.time_grid = std::make_shared<const std::vector<double>>(std::vector<double>{0.0, 0.4, 1.0});
  EXPECT_EQ(settingsDefect(settings).field, "");
}

}  // namespace
}  // namespace mbsopt
