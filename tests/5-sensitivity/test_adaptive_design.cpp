// Design problems on a variable step sequence (NewmarkSettings::time_grid): the steps an
// adaptive run chose at the initial design, frozen, so that the values stay smooth in the design; the
// exact gradients are those of that sequence.
//
// Independent references: the direct method against the discrete adjoint (two derivations of the same
// recursion, each step with its own h), and central differences of the values at the best step.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/integrators/adaptive_newmark.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/gradient_checks.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

/// The problem with the steps an adaptive run takes on its scene (the initial design) at `tolerance`.
DesignProblem onAdaptiveSteps(DesignProblem problem, double tolerance) {
  LocalErrorControl control;
  control.tolerance = {tolerance, 0.0};
  const Scene& scene = problem.scene;
  const AdaptiveRun run = adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, control);
  problem.scene.settings.time_grid = timeGrid(run.trajectory.time);
  return problem;
}

DesignProblem openChain() {
  return onAdaptiveSteps(loadDesignProblem({"chain.yaml", test::kOpenChainProblem}), 1e-7);
}

DesignProblem fourBar() {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  return onAdaptiveSteps(loadDesignProblem(source, {{"settings.end_time", 0.5}}), 1e-7);
}

/// The largest step of a grid over its smallest.
double stepRatio(const std::vector<double>& grid) {
  double smallest = grid[1] - grid[0], largest = smallest;
  for (std::size_t k = 2; k < grid.size(); ++k) {
    smallest = std::min(smallest, grid[k] - grid[k - 1]);
    largest = std::max(largest, grid[k] - grid[k - 1]);
  }
  return largest / smallest;
}

TEST(AdaptiveDesign, AdjointEqualsDirectOnTheSteps) {
  for (const DesignProblem& problem : {openChain(), fourBar()}) {
    ASSERT_GT(stepRatio(*problem.scene.settings.time_grid), 2.0);  // the steps do vary
    const std::vector<ConstraintFunctional> functionals = transcribe(problem);
    const Eigen::VectorXd x = initialPoint(problem);
    test::expectAdjointEqualsDirect(problem, functionals, x);
    // The run is on the grid: its time points are the grid's.
    const DesignResponse response = evaluateDesign(problem, functionals, x);
    const Eigen::VectorXd& time = caseTrajectory(response, 0).time;
    ASSERT_EQ(static_cast<std::size_t>(time.size()), problem.scene.settings.time_grid->size());
    EXPECT_EQ(time[time.size() - 1], problem.scene.settings.time_grid->back());
  }
}

TEST(AdaptiveDesign, CentralDifferencesAgreeOnAClosedLoop) {
  // As for one run at a fixed step (test_exact_gradients.cpp): 1e-6 at the best step.
  const DesignProblem problem = fourBar();
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = designGradient("adjoint", problem, functionals, x);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

TEST(AdaptiveDesign, TheTramwayOnTheStepsItsSceneAsksForHasExactGradients) {
  // settings.integrator: adaptive in a design problem freezes the steps of an adaptive run at the
  // initial design (scene_file.cpp); the artificial variable at 2 makes the cost's constraints active.
  const DesignProblem problem =
      loadDesignProblem(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml"),
                        {ParameterOverride::ofWord("settings.integrator", "adaptive"), {"settings.local_tolerance", 1e-6}});
  ASSERT_TRUE(problem.scene.settings.time_grid);
  EXPECT_GT(stepRatio(*problem.scene.settings.time_grid), 2.0);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  Eigen::VectorXd x = initialPoint(problem);
  x[x.size() - 1] = 2.0;
  const DesignGradient adjoint = test::expectAdjointEqualsDirect(problem, functionals, x);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

TEST(AdaptiveDesign, TheContinuousAdjointRefusesVaryingSteps) {
  const DesignProblem problem = openChain();
  EXPECT_THROW(designGradient("continuous-adjoint", problem, transcribe(problem), initialPoint(problem)),
               std::invalid_argument);
}

}  // namespace
}  // namespace mbsopt
