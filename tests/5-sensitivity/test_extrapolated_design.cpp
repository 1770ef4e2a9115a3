// Design problems run with the extrapolation (settings.integrator: extrapolation): their
// values are the combination of the Newmark runs at h/1 … h/k, and every gradient method differentiates
// that combination exactly (the exact methods run by run, with the same weights).
//
// Independent references: the weights of the even expansion written out (Lagrange's extrapolation in
// h² to h = 0), the runs evaluated as problems of their own at h/j, and central differences of the
// combined values.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/gradient_checks.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

const std::vector<ParameterOverride> kExtrapolated{ParameterOverride::ofWord("settings.integrator", "extrapolation"),
                                                    {"settings.extrapolation_runs", 3.0}};

DesignProblem openChain(const std::vector<ParameterOverride>& overrides) {
  return loadDesignProblem({"chain.yaml", test::kOpenChainProblem}, overrides);
}

DesignProblem fourBar(std::vector<ParameterOverride> overrides) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  overrides.push_back({"settings.end_time", 0.5});
  return loadDesignProblem(source, overrides);
}

TEST(ExtrapolatedDesign, ValuesAreTheLagrangeCombinationOfTheRuns) {
  // No cut joints: the error is even in h, and three runs combine as Lagrange's extrapolation in h²:
  // the result T_{3,2} = −4/5 y(h/2) + 9/5 y(h/3), the check T_{3,3} = y(h)/24 − 16/15 y(h/2) + 81/40 y(h/3).
  const DesignProblem problem = openChain(kExtrapolated);
  ASSERT_EQ(extrapolationRuns(problem), 3);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse combined = evaluateDesign(problem, functionals, x);
  std::vector<Eigen::VectorXd> runs;
  for (const double step : {2e-3, 1e-3, 2e-3 / 3.0})
    runs.push_back(evaluateDesign(openChain({{"settings.step", step}}), functionals, x).constraints);
  const Eigen::VectorXd result = -4.0 / 5.0 * runs[1] + 9.0 / 5.0 * runs[2];
  const Eigen::VectorXd check = runs[0] / 24.0 - 16.0 / 15.0 * runs[1] + 81.0 / 40.0 * runs[2];
  const double scale = result.cwiseAbs().maxCoeff();
  EXPECT_LT((combined.constraints - result).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((combined.constraint_errors - (result - check)).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_EQ(caseTrajectory(combined, 0).time.size(), 2251);  // the finest run's: 1.5 s in steps of h/3
}

TEST(ExtrapolatedDesign, EveryRunEndsAtTheEndTime) {
  // T = 1.5 s on h = 7 ms is not a whole number of steps: the macro step is 1.5 s / 215 (the largest
  // at most 7 ms that divides T), run j takes 215 j steps of it over j, and every run ends at T, or
  // integrals over time would cover different intervals and not combine.
  const DesignProblem problem =
      openChain({ParameterOverride::ofWord("settings.integrator", "extrapolation"), {"settings.extrapolation_runs", 3.0},
                 {"settings.step", 7e-3}});
  const DesignResponse combined = evaluateDesign(problem, transcribe(problem), initialPoint(problem));
  ASSERT_EQ(combined.made_of, ResponseParts::ExtrapolationRuns);
  ASSERT_EQ(combined.parts.size(), 3u);
  for (std::size_t j = 0; j < combined.parts.size(); ++j) {
    const Eigen::VectorXd& time = combined.parts[j].trajectory.time;
    EXPECT_EQ(time.size(), 215 * static_cast<Eigen::Index>(j + 1) + 1);
    EXPECT_EQ(time[time.size() - 1], 1.5);
  }
}

TEST(ExtrapolatedDesign, AdjointEqualsDirectRunByRun) {
  for (const DesignProblem& problem : {openChain(kExtrapolated), fourBar(kExtrapolated)}) {
    const std::vector<ConstraintFunctional> functionals = transcribe(problem);
    const Eigen::VectorXd x = initialPoint(problem);
    const DesignGradient adjoint = test::expectAdjointEqualsDirect(problem, functionals, x);
    ASSERT_TRUE(adjoint.values.has_value());
    // The values an exact method returns are the combination evaluateDesign gives.
    const DesignResponse response = evaluateDesign(problem, functionals, x);
    EXPECT_LE((adjoint.values->constraints - response.constraints).cwiseAbs().maxCoeff(),
              1e-12 * response.constraints.cwiseAbs().maxCoeff());
  }
}

TEST(ExtrapolatedDesign, CentralDifferencesOfTheCombinedValuesAgreeOnAClosedLoop) {
  // The four-bar (cut joints: the error's powers 2, 3, 4, …): the adjoint of the combination against
  // central differences of the combined values at the best step, to 1e-6 as for one run
  // (test_exact_gradients.cpp).
  const DesignProblem problem = fourBar(kExtrapolated);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignGradient adjoint = designGradient("adjoint", problem, functionals, x);
  test::expectCentralDifferencesAtTheBestStep(problem, functionals, x, adjoint, 1e-6);
}

TEST(ExtrapolatedDesign, TheCostFunctionalAndItsErrorComeFromTheRuns) {
  const DesignProblem problem = openChain(kExtrapolated);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse combined = evaluateDesign(problem, functionals, x);
  std::vector<double> runs;
  for (const double step : {2e-3, 1e-3, 2e-3 / 3.0}) {
    const DesignProblem run = openChain({{"settings.step", step}});
    runs.push_back(costFunctional(run, evaluateDesign(run, functionals, x)));
  }
  const double result = -4.0 / 5.0 * runs[1] + 9.0 / 5.0 * runs[2];
  const double check = runs[0] / 24.0 - 16.0 / 15.0 * runs[1] + 81.0 / 40.0 * runs[2];
  EXPECT_NEAR(costFunctional(problem, combined), result, 1e-12 * std::abs(result));
  EXPECT_NEAR(costFunctionalError(problem, combined), result - check, 1e-12 * std::abs(result));
}

}  // namespace
}  // namespace mbsopt
