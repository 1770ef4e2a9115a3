// Extrapolation of the trapezoidal Newmark scheme and the global error estimates (4-integrators/extrapolation,
// 4-integrators/accuracy_control, 4-integrators/integration; docs/integrators.md).
//
// References from outside the code under test:
// - the weights for the even expansion are Lagrange's extrapolation to h = 0 in the variable h²,
//   c_i = Π_{k≠i} n_i² / (n_i² − n_k²), written out here;
// - the oscillator x'' = −ω²x (x₀ = 1, ẋ₀ = 0) has the exact solution cos ωt, and the trapezoidal rule
//   gives x_n = cos nθ with θ = 2 atan(ωh/2) exactly (its amplification matrix is a rotation by θ): so
//   the true global error of every run is known in closed form;
// - Andrews' squeezer's published angles at t = 0.03 s (problems/scenes/hard/reference).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "mbsopt/integrators/accuracy_control.hpp"
#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "tests/integrator_scenes.hpp"

namespace mbsopt {
namespace {

using test::kOmega;
using test::oscillator;
using test::sceneFile;
using test::trueOscillatorError;

TEST(ExtrapolationWeights, EvenPowersAreLagrangeExtrapolationInHSquared) {
  ExtrapolationTableau tableau({2, 4, 6, 8});
  SampledRun empty;
  for (int j = 1; j <= 3; ++j) tableau.add(empty, 1.0 / j);
  const auto lagrange = [](const std::vector<double>& n, std::size_t i) {
    double c = 1.0;
    for (std::size_t k = 0; k < n.size(); ++k)
      if (k != i) c *= n[i] * n[i] / (n[i] * n[i] - n[k] * n[k]);
    return c;
  };
  const Eigen::VectorXd all = tableau.weights(0), last_two = tableau.weights(1);
  ASSERT_EQ(all.size(), 3);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(all[static_cast<Eigen::Index>(i)], lagrange({1, 2, 3}, i), 1e-14);
  EXPECT_NEAR(all[0], 1.0 / 24.0, 1e-15);  // written out: 1/24, −16/15, 81/40
  EXPECT_NEAR(all[1], -16.0 / 15.0, 1e-14);
  EXPECT_NEAR(all[2], 81.0 / 40.0, 1e-14);
  ASSERT_EQ(last_two.size(), 2);
  EXPECT_NEAR(last_two[0], -4.0 / 5.0, 1e-14);
  EXPECT_NEAR(last_two[1], 9.0 / 5.0, 1e-14);
}

TEST(ExtrapolationWeights, EveryPowerOfTheExpansionCancels) {
  // Exponents 2, 3, 4, 5 (the closed loops'): the combination of runs j − k + 1 … j keeps a constant
  // and cancels h^2 … h^(k) for h = 1/n_i.
  const std::vector<int> exponents{2, 3, 4, 5};
  ExtrapolationTableau tableau(exponents);
  SampledRun empty;
  for (int j = 1; j <= 5; ++j) tableau.add(empty, 1.0 / j);
  for (int first = 0; first < 4; ++first) {
    const Eigen::VectorXd c = tableau.weights(first);
    double constant = 0.0;
    for (Eigen::Index i = 0; i < c.size(); ++i) constant += c[i];
    EXPECT_NEAR(constant, 1.0, 1e-12);
    for (Eigen::Index m = 0; m + 1 < c.size(); ++m) {
      double term = 0.0;
      for (Eigen::Index i = 0; i < c.size(); ++i) term += c[i] * std::pow(1.0 / (first + i + 1), exponents[m]);
      EXPECT_NEAR(term, 0.0, 1e-13) << "first run " << first + 1 << ", h^" << exponents[m];
    }
    // The next power is not cancelled: the combination's order is that power.
    if (static_cast<std::size_t>(c.size()) > exponents.size()) continue;  // no next power listed
    double next = 0.0;
    for (Eigen::Index i = 0; i < c.size(); ++i)
      next += c[i] * std::pow(1.0 / (first + i + 1), exponents[static_cast<std::size_t>(c.size() - 1)]);
    EXPECT_GT(std::abs(next), 1e-6);
  }
}

TEST(ErrorExponents, EvenForTheTrapezoidalRuleAllFromTwoWithProjectedLoops) {
  const Scene open = oscillator(1.0);
  EXPECT_EQ(errorExponents(open.model, open.settings), (std::vector<int>{2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24}));
  const Scene loop = sceneFile("problems/scenes/four_bar.yaml");
  const std::vector<int> projected = errorExponents(loop.model, loop.settings);
  EXPECT_EQ(std::vector<int>(projected.begin(), projected.begin() + 4), (std::vector<int>{2, 3, 4, 5}));
}

TEST(GlobalErrorEstimate, IsTheTrueErrorOfTheOscillatorToItsNextOrder) {
  // e_h = e₂h² + e₄h⁴: the estimate 4/3 (y_h − y_{h/2}) = e₂h² + (5/4) e₄h⁴ differs from it by e₄h⁴/4,
  // a fraction of order (ωh)² of the error itself: 4e-5 at h = 1 ms, asserted at 1e-3.
  Scene scene = oscillator(1.0);
  scene.settings.step = 1e-3;
  Trajectory run = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const double theta = 2.0 * std::atan(kOmega * scene.settings.step / 2.0);
  Eigen::VectorXd truth(run.time.size());
  for (Eigen::Index k = 0; k < run.time.size(); ++k)
    truth[k] = std::cos(static_cast<double>(k) * theta) - std::cos(kOmega * run.time[k]);
  ASSERT_NEAR((run.q.row(0).transpose() - (truth + (kOmega * run.time).array().cos().matrix())).cwiseAbs().maxCoeff(), 0.0,
              1e-12);  // the run is the rule's closed form
  const EstimatedRun estimated = estimateGlobalError(scene.model, scene.settings, std::move(run), scene.q0, scene.v0);
  const double largest = truth.cwiseAbs().maxCoeff();
  EXPECT_GT(largest, 1e-5);
  EXPECT_LT((estimated.q_error.row(0).transpose() - truth).cwiseAbs().maxCoeff(), 1e-3 * largest);
  EXPECT_NEAR(estimated.positionError(), largest, 1e-3 * largest);
  EXPECT_EQ(estimated.steps, (std::vector<double>{1e-3, 5e-4}));
}

TEST(Extrapolation, OscillatorConvergesAtItsOrderAndItsEstimateIsItsError) {
  // Three runs without cut joints: T_{3,2} of order 4 (h², removed), its estimate T_{3,3} − T_{3,2}
  // equal to its error up to a fraction of order (ωH)². Order checked two-sided between H and H/2.
  Scene scene = oscillator(2.0);
  double previous = 0.0;
  for (const double H : {0.02, 0.01}) {
    scene.settings.step = H;
    const EstimatedRun run = extrapolatedNewmark(scene.model, scene.settings, 3, scene.q0, scene.v0);
    EXPECT_EQ(run.order, 4);
    EXPECT_EQ(run.steps, (std::vector<double>{H, H / 2, H / 3}));
    ASSERT_EQ(run.trajectory.time.size(), std::lround(2.0 / H) + 1);
    const double error = trueOscillatorError(run.trajectory);
    EXPECT_NEAR(run.positionError() / error, 1.0, 0.1) << "H = " << H;
    if (previous > 0.0) {
      const double order = std::log2(previous / error);
      EXPECT_GT(order, 3.7);
      EXPECT_LT(order, 4.3);
    }
    previous = error;
  }
}

TEST(Extrapolation, RefusesASchemeWhoseErrorIsNotEvenInH) {
  Scene scene = oscillator(0.1);
  scene.settings.gamma = 0.6;
  scene.settings.beta = 0.3025;
  EXPECT_THROW(extrapolatedNewmark(scene.model, scene.settings, 3, scene.q0, scene.v0), std::invalid_argument);
  EXPECT_NE(extrapolationDefect(scene.settings).find("trapezoidal"), std::string::npos);
  scene = oscillator(0.1);
  scene.settings.accept_by_contraction_rate = true;
  EXPECT_THROW(estimateGlobalError(scene.model, scene.settings, Trajectory{}, scene.q0, scene.v0), std::invalid_argument);
}

/// The six runs of macro step H on `scene` (steps H/j, each stretched by `stretch`, to an end time
/// stretched alike: the same steps, a few ulps longer), with the round-off probe when `probe`.
ExtrapolationTableau sixRuns(const Scene& scene, double H, double stretch, bool probe) {
  NewmarkSettings macro = scene.settings;
  macro.step = H * (1.0 + stretch);
  macro.end_time *= 1.0 + stretch;
  const long outputs = stepsToCover(macro.end_time, H);
  ExtrapolationTableau tableau(errorExponents(scene.model, macro));
  for (int j = 1; j <= 6; ++j) {
    NewmarkSettings run = macro;
    run.step = macro.step / j;
    tableau.add(sampledNewmarkRun(scene.model, run, scene.q0, scene.v0, j, outputs), run.step);
  }
  if (probe) tableau.addRoundOffProbe(roundOffProbe(scene.model, macro, 6, scene.q0, scene.v0, outputs));
  return tableau;
}

TEST(RoundOffFloor, IsTheDifferenceOfTwoRoundingsOfTheSameCombination) {
  // The same six runs of the four-bar with steps a few ulps longer (48ε: not the probe's 16ε) have the
  // same truncation error to 1e-13 of it but round differently at every step: their result differs
  // from the first by the combination's round-off alone, √2 times its floor if the floor is a
  // faithful measure of it (the probe is a third rounding). Both sides are largest values over 400
  // time points and 4 coordinates of sums of many rounding errors; the factor of 10 either way that the estimate is held to.
  const Scene scene = sceneFile("problems/scenes/four_bar.yaml");
  const ExtrapolationTableau a = sixRuns(scene, 0.01, 0.0, true);
  const ExtrapolationTableau b = sixRuns(scene, 0.01, 48.0 * std::numeric_limits<double>::epsilon(), false);
  const double difference = (a.result().q - b.result().q).cwiseAbs().maxCoeff();
  const Eigen::MatrixXd floors = a.roundOffFloor(&SampledRun::q);
  const double floor = floors.maxCoeff();
  EXPECT_GT(difference, 1e-13) << "the two roundings must differ beyond the last digits for the check to mean something";
  EXPECT_LT(difference, 10.0 * std::numbers::sqrt2 * floor);
  EXPECT_GT(difference, 0.1 * std::numbers::sqrt2 * floor);
  EXPECT_EQ(a.probedRuns(), 6);
  // It never falls: the largest difference up to each time.
  EXPECT_TRUE(((floors.rightCols(floors.cols() - 1) - floors.leftCols(floors.cols() - 1)).array() >= 0.0).all());
  // A fixed-step extrapolation of four runs or more includes it in its estimate, and says how large it is.
  NewmarkSettings macro = scene.settings;
  macro.step = 0.01;
  const EstimatedRun run = extrapolatedNewmark(scene.model, macro, 6, scene.q0, scene.v0);
  ASSERT_TRUE(run.round_off_floor.has_value());
  EXPECT_GE(run.positionError(), *run.round_off_floor);
  EXPECT_FALSE(extrapolatedNewmark(scene.model, macro, kProbedRuns - 1, scene.q0, scene.v0).round_off_floor.has_value());
}

TEST(AccuracyControl, OscillatorMeetsEveryToleranceAndSaysHowWell) {
  // The true error against cos ωt stays below the tolerance (absolute; the run accepted at half of it,
  // asserted at twice it) and within the factor of 10 of its estimate that a run driven by accuracy promises.
  const Scene scene = oscillator(3.0);
  for (const double tolerance : {1e-3, 1e-5, 1e-7, 1e-9}) {
    AccuracyGoal goal;
    goal.tolerance = {tolerance, 0.0};
    const AccurateRun run = simulateToAccuracy(scene.model, scene.settings, scene.q0, scene.v0, goal);
    const double error = trueOscillatorError(run.run.trajectory);
    EXPECT_LE(run.weighted_error, kAcceptedFraction);
    EXPECT_LT(error, tolerance * 2.0) << tolerance;
    EXPECT_LT(error, 10.0 * run.run.positionError()) << tolerance;
    EXPECT_LT(run.run.positionError(), 10.0 * error) << tolerance;
  }
}

TEST(AccuracyControl, OutputTimesAreTheMultiplesOfTheOutputStep) {
  const Scene scene = oscillator(1.0);
  IntegrationRequest request;
  request.integrator.name = "extrapolation";
  request.accuracy = ErrorTolerance{1e-6, 1e-6};
  request.output_step = 0.125;
  const Integration integration = integrate(scene.model, scene.settings, scene.q0, scene.v0, request);
  const Eigen::VectorXd& time = integration.run.trajectory.time;
  ASSERT_EQ(time.size(), 9);
  for (Eigen::Index k = 0; k < time.size(); ++k) EXPECT_NEAR(time[k], 0.125 * static_cast<double>(k), 1e-12);
  EXPECT_EQ(integration.run.q_error.cols(), 9);
  EXPECT_EQ(integration.run.sensor_error.rows(), 9);
  EXPECT_LT(trueOscillatorError(integration.run.trajectory), 2e-6);
  // The macro step divides the output step.
  const double per_output = 0.125 / integration.control->macro_step;
  EXPECT_NEAR(per_output, std::round(per_output), 1e-9);
}

TEST(AccuracyControl, AndrewsSqueezerMeetsThePublishedAngles) {
  test::expectAndrewsMeetsThePublishedAngles("extrapolation", {1e-4, 1e-7});
}

TEST(AccuracyControl, ATooCoarseStartIsRefinedAndAnUnreachableGoalSaysWhatItReached) {
  // A first macro step of the whole 30 ms on the squeezer makes Newton fail; the controller divides
  // it and goes on, and the rejected attempt keeps the failure's message. Three attempts of at most two
  // runs at 1e-14 cannot succeed: the error names the closest estimate.
  const Scene scene = sceneFile("problems/scenes/hard/andrews_squeezer.yaml");
  AccuracyGoal goal;
  goal.tolerance = {1e-4, 0.0};
  goal.first_macro_step = 0.03;
  const AccurateRun run = simulateToAccuracy(scene.model, scene.settings, scene.q0, scene.v0, goal);
  ASSERT_FALSE(run.rejected.empty());
  EXPECT_NE(run.rejected.front().failure.find("Newton did not converge"), std::string::npos) << run.rejected.front().failure;
  goal.first_macro_step = 0.0;
  goal.tolerance = {1e-14, 0.0};
  goal.max_runs = 2;
  goal.max_attempts = 3;
  try {
    simulateToAccuracy(scene.model, scene.settings, scene.q0, scene.v0, goal);
    FAIL() << "1e-14 with order 2 in three attempts cannot be met";
  } catch (const AccuracyError& e) {
    EXPECT_NE(std::string(e.what()).find("no run met the accuracy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("times the tolerance"), std::string::npos) << e.what();
  }
  goal.tolerance = {-1.0, 1e-3};
  EXPECT_THROW(simulateToAccuracy(scene.model, scene.settings, scene.q0, scene.v0, goal), std::invalid_argument);
}

TEST(Integration, RegistryNamesEveryIntegratorOnce) {
  EXPECT_EQ(integratorNameList(), "newmark, extrapolation, adaptive");
  EXPECT_EQ(integratorInfo("extrapolation").max_runs, 6);
  try {
    integratorInfo("rk4");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: newmark, extrapolation, adaptive"), std::string::npos);
  }
}

TEST(Integration, AFixedNewmarkStepKeepsEveryNthPointAndEndsAtTheEndTime) {
  const Scene scene = oscillator(1.0);
  IntegrationRequest request;
  request.output_step = 0.01;  // 10 steps of the scene's 1 ms
  const Integration kept = integrate(scene.model, scene.settings, scene.q0, scene.v0, request);
  EXPECT_FALSE(kept.estimated);
  ASSERT_EQ(kept.run.trajectory.time.size(), 101);
  const Trajectory every = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  for (Eigen::Index k = 0; k < 101; ++k) EXPECT_EQ(kept.run.trajectory.q(0, k), every.q(0, 10 * k));
  // 1 s is not a whole number of 10.5 ms: 96 equal intervals of 1/96 s (the most at most 10.5 ms), each
  // of 11 equal steps (the fewest at most 1 ms), the last output at 1 s.
  request.output_step = 0.0105;
  const Integration shortened = integrate(scene.model, scene.settings, scene.q0, scene.v0, request);
  const Eigen::VectorXd& time = shortened.run.trajectory.time;
  ASSERT_EQ(time.size(), 97);
  EXPECT_EQ(time[96], 1.0);
  EXPECT_NEAR(time[1], 1.0 / 96.0, 1e-15);
  NewmarkSettings fine = scene.settings;
  fine.step = 1.0 / (96.0 * 11.0);
  const Trajectory steps = NewmarkIntegrator(scene.model, fine).simulate(scene.q0, scene.v0);
  ASSERT_EQ(steps.time.size(), 96 * 11 + 1);
  for (Eigen::Index k = 0; k < 97; ++k) EXPECT_EQ(shortened.run.trajectory.q(0, k), steps.q(0, 11 * k));
}

}  // namespace
}  // namespace mbsopt
