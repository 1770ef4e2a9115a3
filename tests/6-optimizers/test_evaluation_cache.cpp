// The reported-point rule of EvaluationCache::conclude on a problem small enough to know every
// point's values: an epigraph cost, min b subject to φ(y) − b ≤ 0 with φ(y) = y² + 1, whose
// artificial variable b may undercut φ by as much as the feasibility tolerance allows.
#include <gtest/gtest.h>

#include <utility>

#include "mbsopt/optimizers/evaluation_cache.hpp"

namespace mbsopt {
namespace {

constexpr double kTolerance = 1e-6;  // the feasibility tolerance on φ − b

class Epigraph : public NlpProblem {
 public:
  Eigen::Index variableCount() const override { return 2; }
  Eigen::Index inequalityCount() const override { return 1; }
  Eigen::VectorXd lowerBounds() const override { return Eigen::Vector2d(-2.0, 0.0); }
  Eigen::VectorXd upperBounds() const override { return Eigen::Vector2d(2.0, 10.0); }
  Eigen::VectorXd start() const override { return Eigen::Vector2d(1.0, 2.0); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    const double phi = x[0] * x[0] + 1.0;
    out.cost = x[1];
    out.reported_cost = phi;  // the physical cost, which b bounds
    out.constraints = Eigen::VectorXd::Constant(1, phi - x[1]);
    if (gradients) {
      out.cost_gradient.resize(2);
      out.cost_gradient << 0.0, 1.0;
      out.constraint_jacobian.resize(1, 2);
      out.constraint_jacobian << 2.0 * x[0], -1.0;
    }
  }
};

class ReportedPointRule : public testing::Test {
 protected:
  Epigraph problem;
  OptimizerOptions options;
  OptimizerResult result;
  ReportedPointRule() { options.feasibility_tolerance = kTolerance; }

  /// Evaluates and records each point in turn, as an algorithm's iterates.
  void iterate(EvaluationCache& cache, std::initializer_list<Eigen::Vector2d> points) {
    for (const Eigen::Vector2d& x : points) cache.recordIteration(x, result);
  }
};

// The optimum is (0, 1), where the multiplier of φ − b ≤ 0 is 1. An earlier iterate (0, 1 − 0.5 tol)
// has the lower b (what "the lowest b_{k+1}" would report) and the same physical cost φ = 1: a
// converged run reports its own final point.
TEST_F(ReportedPointRule, AConvergedRunReportsItsFinalPointNotAnEarlierOneWhoseArtificialVariableUndercuts) {
  EvaluationCache cache(problem, options);
  const Eigen::Vector2d undercut(0.0, 1.0 - 0.5 * kTolerance), optimum(0.0, 1.0);
  iterate(cache, {problem.start(), undercut, optimum});
  result.status = OptimizerStatus::Converged;
  cache.conclude(result, optimum);
  EXPECT_EQ(result.status, OptimizerStatus::Converged) << result.message;
  EXPECT_EQ(result.reported, ReportedPoint::Final);
  EXPECT_EQ(result.x, optimum);
  EXPECT_EQ(result.reported_cost, 1.0);
  ASSERT_TRUE(result.first_order);
  EXPECT_LT(result.first_order->residual, 1e-12);
}

// A run that stopped short is judged by the physical cost, not by b: of (0.5, 1.25) and the
// undercutting (0.1, 1.01 − 0.5 tol), the second (φ = 1.01) is cheaper although (0.5, 1.25) has
// no lower b; a later point of equal φ wins over an earlier one.
TEST_F(ReportedPointRule, AStoppedRunReportsTheCheapestFeasiblePhysicalCostTheLatestOfEquals) {
  EvaluationCache cache(problem, options);
  const Eigen::Vector2d cheap(0.1, 1.01 - 0.5 * kTolerance), same_cost(-0.1, 1.01), last(0.5, 1.25);
  iterate(cache, {problem.start(), cheap, same_cost, last});
  result.status = OptimizerStatus::MaxIterations;
  cache.conclude(result, last);
  EXPECT_EQ(result.reported, ReportedPoint::CheapestFeasible);
  EXPECT_EQ(result.x, same_cost);
  EXPECT_NEAR(result.reported_cost, 1.01, 1e-15);
}

// A trial the algorithm evaluated and rejected (SDCC's, Ipopt's line search) is no iterate: however
// cheap, it is not reported, for the history, the CSV and the plots could not show it.
TEST_F(ReportedPointRule, AnEvaluatedTrialThatIsNoIterateIsNotReported) {
  EvaluationCache cache(problem, options);
  const Eigen::Vector2d iterate_point(0.5, 1.25), trial(0.1, 1.01);
  iterate(cache, {problem.start(), iterate_point});
  cache.at(trial, false);
  result.status = OptimizerStatus::MaxIterations;
  cache.conclude(result, iterate_point);
  EXPECT_EQ(result.reported, ReportedPoint::CheapestFeasible);
  EXPECT_EQ(result.x, iterate_point);
}

// A point below φ by more than the tolerance is infeasible, however low its b: it is never the
// reported point while a feasible one exists.
TEST_F(ReportedPointRule, APointBeyondTheToleranceIsNotReportedHoweverCheap) {
  EvaluationCache cache(problem, options);
  const Eigen::Vector2d beyond(0.0, 1.0 - 2.0 * kTolerance), feasible(0.5, 1.25);
  iterate(cache, {feasible, beyond});
  result.status = OptimizerStatus::MaxIterations;
  cache.conclude(result, beyond);
  EXPECT_EQ(result.reported, ReportedPoint::CheapestFeasible);
  EXPECT_EQ(result.x, feasible);
}

// An algorithm whose own test passed at a point that is not first-order optimal ((1, 2): the
// constraint is active, but ∂b = 1 and ∂φ/∂y = 2 cannot both be balanced by one multiplier) or is
// infeasible ((0, 0.9): φ − b = 0.1) fails, and the report is the cheapest feasible iterate,
// not the point where it stopped.
TEST_F(ReportedPointRule, AConvergenceClaimAtANonOptimalOrInfeasiblePointReportsTheCheapestFeasibleOne) {
  const Eigen::Vector2d cheaper(0.5, 1.25);
  for (const auto& [stopped, why] : {std::pair{Eigen::Vector2d(1.0, 2.0), "not first-order optimal"},
                                     std::pair{Eigen::Vector2d(0.0, 0.9), "beyond the problem's tolerances"}}) {
    EvaluationCache cache(problem, options);
    result = {};
    iterate(cache, {cheaper, stopped});
    result.status = OptimizerStatus::Converged;
    cache.conclude(result, stopped);
    EXPECT_EQ(result.status, OptimizerStatus::Failed);
    EXPECT_NE(result.message.find(why), std::string::npos) << result.message;
    EXPECT_EQ(result.reported, ReportedPoint::CheapestFeasible);
    EXPECT_EQ(result.x, cheaper);
  }
}

}  // namespace
}  // namespace mbsopt
