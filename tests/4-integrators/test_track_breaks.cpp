// Where the accelerations jump (a curve slider passing a jump of its track's curvature) and the time
// grids graded there (4-integrators/track_breaks.hpp).
//
// Independent references: the crossing times of a slider whose arc length is a quadratic in time (closed
// form; the cubic through two time points reproduces a quadratic exactly), the grid's defining
// properties, the convergence order two-sided from successive differences (a graded grid's error falls
// as h², docs/integrators.md §11), the direct method against the discrete adjoint and central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/integrators/track_breaks.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/gradient_checks.hpp"

namespace mbsopt {
namespace {

/// A pendulum hanging from a slider on a track whose curvature jumps twice, at s = 3 (straight into an
/// arc) and s = 10 (an arc into a straight), and runs on without a jump through a clothoid between two
/// arcs. The slider is driven at s(t) = 1 + 2t + t²/2, or free (and then, translating a point mass
/// without forces along it, s(t) = 1 + 2t).
struct SliderOnTrack {
  Model model;
  Eigen::VectorXd q0, v0;

  explicit SliderOnTrack(bool driven) {
    Track track;
    track.straight(3.0).arc(5.0, 0.4).clothoid(2.0, 0.1).arc(10.0, 0.3).straight(5.0);
    const FrameIndex slider = model.addCurveSlider("slider", Model::ground, model.addTrack("rail", track),
                                                   SliderOrientation::Translate);
    if (driven) {
      model.drive("slider", TimeFunction::polynomial({1.0, 2.0, 0.5}));
      const FrameIndex arm = model.addRevolute("arm", slider, Eigen::Vector3d::UnitZ());
      model.addBody("bob", arm, 1.0, Eigen::Vector3d(0.0, -1.0, 0.0), 0.01 * Eigen::Matrix3d::Identity());
      model.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
    } else {
      model.addBody("bead", slider, 2.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
    }
    q0 = Eigen::VectorXd::Zero(model.coordinateCount());
    v0 = Eigen::VectorXd::Zero(model.coordinateCount());
    q0[model.coordinate("slider")] = 1.0;
    v0[model.coordinate("slider")] = 2.0;
  }

  Trajectory run(double step, double end_time) const {
    NewmarkSettings settings;
    settings.step = step;
    settings.end_time = end_time;
    return NewmarkIntegrator(model, settings).simulate(q0, v0);
  }
};

TEST(TrackBreaks, ADrivenSliderCrossesTheJumpsWhereItsArcLengthSays) {
  const SliderOnTrack scene(true);
  ASSERT_TRUE(hasCurvatureJumps(scene.model));
  // s(t) = 1 + 2t + t²/2 reaches 3 at −2 + √8 and 10 at −2 + √22 (the clothoid's ends, s = 5 and 7,
  // are no jumps).
  const std::vector<double> times = curvatureJumpTimes(scene.model, scene.run(0.05, 3.0));
  ASSERT_EQ(times.size(), 2u);
  EXPECT_NEAR(times[0], -2.0 + std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(times[1], -2.0 + std::sqrt(22.0), 1e-12);
}

TEST(TrackBreaks, AFreeSliderIsFoundWhereItsTrajectoryCrosses) {
  const SliderOnTrack scene(false);
  // Nothing acts along the track: ṡ stays 2 and the jumps are passed at t = 1 and 4.5.
  const std::vector<double> times = curvatureJumpTimes(scene.model, scene.run(0.1, 5.0));
  ASSERT_EQ(times.size(), 2u);
  EXPECT_NEAR(times[0], 1.0, 1e-12);
  EXPECT_NEAR(times[1], 4.5, 1e-12);
  // A run that ends before the second jump finds only the first.
  EXPECT_EQ(curvatureJumpTimes(scene.model, scene.run(0.1, 3.0)).size(), 1u);
}

TEST(TrackBreaks, ATrackThatEndsInAnArcJumpsAtItsEnd) {
  // Beyond its end a track runs on straight: a slider driven past the end of an arc at s = 2 + 1.5
  // feels the curvature drop to zero there.
  Model model;
  Track track;
  track.straight(2.0).arc(3.0, 0.5);
  const FrameIndex slider = model.addCurveSlider("slider", Model::ground, model.addTrack("rail", track));
  const FrameIndex arm = model.addRevolute("arm", slider, Eigen::Vector3d::UnitZ());  // something free
  model.addBody("bob", arm, 1.0, Eigen::Vector3d(0.0, -1.0, 0.0), 0.01 * Eigen::Matrix3d::Identity());
  model.drive("slider", TimeFunction::polynomial({0.0, 1.0}));
  NewmarkSettings settings;
  settings.step = 0.1;
  settings.end_time = 5.0;
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(model.coordinateCount());
  Eigen::VectorXd v0 = q0;
  v0[model.coordinate("slider")] = 1.0;
  const std::vector<double> times = curvatureJumpTimes(model, NewmarkIntegrator(model, settings).simulate(q0, v0));
  ASSERT_EQ(times.size(), 2u);
  EXPECT_NEAR(times[0], 2.0, 1e-12);
  EXPECT_NEAR(times[1], 3.5, 1e-12);
}

TEST(TrackBreaks, ATrackWithClothoidsHasNoJumps) {
  Model model;
  Track track;
  track.straight(2.0).clothoid(3.0, 0.2).arc(5.0, 0.5).clothoid(3.0, 0.0).straight(2.0);
  model.addBody("cart", model.addCurveSlider("slider", Model::ground, model.addTrack("rail", track)), 1.0,
                Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  EXPECT_FALSE(hasCurvatureJumps(model));
}

TEST(TrackBreaks, AGradedGridCrossesEachBreakInOneShortStep) {
  const double end_time = 1.005, h = end_time / 101;  // the uniform grid of at most 1e-2 s: 101 steps
  const std::vector<double> breaks = {0.0, 0.2, 0.2037, 0.5, 1.5};  // 0 and beyond the end are ignored
  const std::vector<double> grid = *gradedTimeGrid(1e-2, end_time, breaks);
  const double eta = crossingStep(h, end_time);
  EXPECT_DOUBLE_EQ(eta, h * h / end_time);
  ASSERT_EQ(grid.front(), 0.0);
  EXPECT_EQ(grid.back(), end_time);
  for (std::size_t k = 1; k < grid.size(); ++k) {
    ASSERT_GT(grid[k] - grid[k - 1], 0.24 * eta);      // no step below η/4 where two breaks' points interleave
    ASSERT_LT(grid[k] - grid[k - 1], 1.5 * h + 1e-15);  // the step joining the graded and uniform points
  }
  for (double t : {0.2, 0.2037, 0.5}) {
    const auto after = std::upper_bound(grid.begin(), grid.end(), t);
    ASSERT_TRUE(after != grid.begin() && after != grid.end());
    EXPECT_LE(*after - *(after - 1), eta * (1 + 1e-9)) << "the step across " << t;
  }
  // Far from the breaks the grid is the uniform one, and there are few graded points per break:
  // 2 log₂(2h/η) ≈ 16 each here.
  for (double t : {0.05, 0.8, 0.99}) {
    const auto at = std::lower_bound(grid.begin(), grid.end(), std::round(t / h) * h - 1e-12);
    ASSERT_TRUE(at != grid.end());
    EXPECT_NEAR(*at, std::round(t / h) * h, 1e-15);
  }
  EXPECT_LT(grid.size(), 102u + 3 * 2 * 17);
}

/// The tramway of problems/scenes/tramway.yaml at its start design.
Scene tramway() {
  return loadScene(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml")).scene;
}

TEST(TrackBreaks, TheTramwayOnGradedGridsConvergesAtSecondOrder) {
  const Scene scene = tramway();
  const Trajectory base = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const std::vector<double> breaks = curvatureJumpTimes(scene.model, base);
  // The front bogie, driven at s = 10 + 3.7 t, enters the arc (s = 12) and leaves it (s = 12 + 7π); the
  // rear bogie, a cut joint's free arc length 9 m behind, passes both about 2.4 s later.
  ASSERT_EQ(breaks.size(), 4u);
  EXPECT_NEAR(breaks[0], 2.0 / 3.7, 1e-12);
  EXPECT_NEAR(breaks[2], (2.0 + 7.0 * M_PI) / 3.7, 1e-12);
  EXPECT_NEAR(breaks[1] - breaks[0], 2.4, 0.1);
  // The articulation angle at 11 s on graded grids of h = 8, 4, 2, 1 ms: successive differences fall
  // by 4 (order 2, measured 1.9-2.0); on uniform grids a step across each jump is first order.
  const Eigen::Index articulation = scene.model.coordinate("articulation");
  const auto at11 = [&](double h, bool graded) {
    NewmarkSettings settings = scene.settings;
    settings.step = h;
    if (graded) settings.time_grid = gradedTimeGrid(h, settings.end_time, breaks);
    const Trajectory run = NewmarkIntegrator(scene.model, settings).simulate(scene.q0, scene.v0);
    Eigen::Index k;
    (run.time.array() - 11.0).abs().minCoeff(&k);
    EXPECT_NEAR(run.time[k], 11.0, 1e-9);
    return run.q(articulation, k);
  };
  std::vector<double> graded;
  for (double h : {8e-3, 4e-3, 2e-3, 1e-3}) graded.push_back(at11(h, true));
  for (std::size_t k = 0; k + 2 < graded.size(); ++k) {
    const double order = std::log2(std::abs(graded[k] - graded[k + 1]) / std::abs(graded[k + 1] - graded[k + 2]));
    EXPECT_GE(order, 1.7);
    EXPECT_LE(order, 2.3);
  }
  // The graded 1 ms run's error (its difference from 2 ms over 3) against the uniform 1 ms run's: 50× smaller or more
  // (measured 4e-9 against 1.4e-5).
  const double graded_error = std::abs(graded[2] - graded[3]) / 3.0;
  EXPECT_LT(50.0 * graded_error, std::abs(at11(1e-3, false) - graded[3]));
}

TEST(TrackBreaks, TheTramwayOnAGradedGridHasExactGradients) {
  // The problem of tramway.yaml on a grid of 4 ms graded at its break times: its steps run from 4 ms
  // down to η = 1.3 µs across each jump. The artificial variable at 2 makes the cost's constraints active.
  DesignProblem problem = loadDesignProblem(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml"));
  const Scene& scene = problem.scene;
  const std::vector<double> breaks =
      curvatureJumpTimes(scene.model, NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0));
  problem.scene.settings.time_grid = gradedTimeGrid(4e-3, scene.settings.end_time, breaks);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  Eigen::VectorXd x = initialPoint(problem);
  x[x.size() - 1] = 2.0;
  const DesignGradient adjoint = test::expectAdjointEqualsDirect(problem, functionals, x);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

}  // namespace
}  // namespace mbsopt
