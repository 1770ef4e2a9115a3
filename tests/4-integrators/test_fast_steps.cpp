// `simulate --fast-steps` (NewmarkSettings::newton_truncation_fraction, reuse_svd_rotations): each step
// solved only as precisely as it approximates the motion. What it must keep: the run's true error
// (against the test set's published angles of Andrews' squeezer, and against the extrapolation of
// the default runs on the four-bar), the loops closed at position level, a global error estimate
// that still holds; what it must buy: fewer Newton iterations (a deterministic count). What it must
// refuse: extrapolation, whose higher orders its Newton errors would cap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "tests/integrator_scenes.hpp"

namespace mbsopt {
namespace {

/// The largest error of Andrews' squeezer's angles at 0.03 s against the published values.
double andrewsError(const Trajectory& t) {
  const Eigen::Index last = t.time.size() - 1;
  double error = 0.0;
  for (Eigen::Index s = 0; s < 7; ++s)
    error = std::max(error, std::abs(t.sensors(last, s) - test::kAndrewsPublished[static_cast<std::size_t>(s)]));
  return error;
}

// Each step's Newton error is at most κ = 1e-3 of its local truncation error, so the errors it adds
// to the run are at most κ times the sum of the local errors' magnitudes, carried to the end. That
// sum exceeds the global error where local errors cancel, by a factor measured at ~17 on the four-bar
// (κ = 1e-2 grew its error by 17 %): 2 % is κ times a cancellation of 20. The iterations: Newton
// stops 4-6 orders of magnitude sooner at these steps, at a contraction of 0.01-0.1 per iteration.
TEST(FastSteps, AndrewsSqueezerKeepsItsErrorInHalfTheNewtonIterations) {
  const Scene scene = test::sceneFile("problems/scenes/hard/andrews_squeezer.yaml");
  for (const double h : {5e-5, 3.125e-5, 2e-5}) {
    NewmarkSettings settings = scene.settings;
    settings.step = h;
    settings.end_time = 0.03;
    const Trajectory exact = NewmarkIntegrator(scene.model, settings).simulate(scene.q0, scene.v0);
    const Trajectory quick = NewmarkIntegrator(scene.model, withFastSteps(settings)).simulate(scene.q0, scene.v0);
    const double e_exact = andrewsError(exact), e_fast = andrewsError(quick);
    EXPECT_GT(e_exact, 1e-5) << h;  // the discretisation's error, far above the published values' 1e-9
    EXPECT_NEAR(e_fast, e_exact, 0.02 * e_exact) << h;
    EXPECT_LT(quick.statistics.newton_iterations, exact.statistics.newton_iterations / 1.5) << h;
    // Closed at position level: the closure rows at βh² times Newton's error (≤ 1e-3 rad/s² here),
    // far below the run check's 1e-6 of the reach, which the run passed.
    EXPECT_LT(quick.statistics.max_closure_error, 1e-9) << h;
  }
}

// The four-bar at h = 5 ms and 1 ms, against the extrapolation of default runs to 1e-10 (its own
// estimate; the runs' errors are 1e-3 … 4e-5): the same true error within 2 %, as above, and the
// error estimate from the same run at h/2 still within 5 % of the truth (Newton's errors, at most
// κ·20 = 2 % of each run's error, enter 4/3 (y_h − y_h/2)).
TEST(FastSteps, TheFourBarKeepsItsErrorAndItsErrorEstimate) {
  const Scene scene = test::sceneFile("problems/scenes/four_bar.yaml");
  NewmarkSettings settings = scene.settings;
  settings.end_time = 4.0;
  IntegrationRequest reference_request;
  reference_request.integrator.name = "extrapolation";
  reference_request.accuracy = ErrorTolerance{1e-10, 0.0};
  reference_request.output_step = 0.1;
  const Integration reference = integrate(scene.model, settings, scene.q0, scene.v0, reference_request);
  const Trajectory& truth = reference.run.trajectory;
  for (const double h : {5e-3, 1e-3}) {
    settings.step = h;
    IntegrationRequest request;
    request.output_step = 0.1;
    request.estimate_error = true;
    const Integration exact = integrate(scene.model, settings, scene.q0, scene.v0, request);
    const Integration quick = integrate(scene.model, withFastSteps(settings), scene.q0, scene.v0, request);
    ASSERT_EQ(quick.run.trajectory.time.size(), truth.time.size());
    const auto worst = [&](const Eigen::MatrixXd& q) { return (q - truth.q).cwiseAbs().maxCoeff(); };
    const double e_exact = worst(exact.run.trajectory.q), e_fast = worst(quick.run.trajectory.q);
    EXPECT_NEAR(e_fast, e_exact, 0.02 * e_exact) << h;
    const Eigen::MatrixXd true_error = quick.run.trajectory.q - truth.q;
    EXPECT_LT((quick.run.q_error - true_error).cwiseAbs().maxCoeff(), 0.05 * true_error.cwiseAbs().maxCoeff()) << h;
    EXPECT_LT(quick.run.trajectory.statistics.newton_iterations, exact.run.trajectory.statistics.newton_iterations / 1.5)
        << h;
  }
}

TEST(FastSteps, ExtrapolationRefusesThemAndTheHalvedRunsEstimateAllowsThem) {
  NewmarkSettings settings;
  settings.newton_truncation_fraction = kNewtonTruncationFraction;
  EXPECT_NE(extrapolationDefect(settings).find("--fast-steps"), std::string::npos) << extrapolationDefect(settings);
  EXPECT_EQ(halvingDefect(settings, "the estimate"), "");
  settings.newton_truncation_fraction = 1.5;
  EXPECT_EQ(settingsDefect(settings).field, "newton_truncation_fraction");
}

}  // namespace
}  // namespace mbsopt
