// Every optimizer behind the common interface on problems with known optima (docs/design.md §5): it
// reaches the optimum within its tolerance, or says cleanly why it cannot (MMA and CCSAQ take no
// equality constraints); it never calls an infeasible point converged; it pays once per point.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "mbsopt/optimizers/latin_hypercube.hpp"
#include "mbsopt/optimizers/optimizer.hpp"
#include "tests/analytic_problems.hpp"

namespace mbsopt {
namespace {

/// Tight enough that each algorithm's own stopping test, not the budget, ends the runs below.
OptimizerOptions tightOptions() {
  OptimizerOptions options;
  options.max_iterations = 1000;
  options.tolerance = 1e-10;
  options.feasibility_tolerance = 1e-8;
  return options;
}

class EveryOptimizer : public testing::TestWithParam<std::string> {};

TEST_P(EveryOptimizer, FindsTheBoundConstrainedMinimumOfAQuadratic) {
  test::BoundedQuadratic problem;
  const OptimizerResult r = minimize(GetParam(), problem, tightOptions());
  EXPECT_EQ(r.status, OptimizerStatus::Converged) << r.message;
  EXPECT_NEAR(r.x[0], 1.0, 1e-6);
  EXPECT_NEAR(r.x[1], 0.5, 1e-4);  // |∂f/∂x₁| = 2|x₁ − ½|: a relative f tolerance of 1e-10 allows ~1e-5
  EXPECT_NEAR(r.cost, 1.0, 1e-8);
  EXPECT_FALSE(r.history.empty());
  EXPECT_EQ(r.iterations, static_cast<int>(r.history.size()));
}

// The optimum satisfies the KKT conditions: g = 0 and ∇f = −μ∇g with μ ≥ 0. μ is the least-squares
// multiplier at the returned point; the residual is relative to |∇f| ≈ 0.2 there.
TEST_P(EveryOptimizer, FindsTheKktPointOfRosenbrockInTheUnitDisc) {
  test::RosenbrockInDisc problem;
  const OptimizerResult r = minimize(GetParam(), problem, tightOptions());
  ASSERT_EQ(r.status, OptimizerStatus::Converged) << r.message;
  NlpEvaluation e;
  problem.evaluate(r.x, true, e);
  EXPECT_NEAR(e.constraints[0], 0.0, 1e-6);
  const Eigen::VectorXd grad_f = e.cost_gradient, grad_g = e.constraint_jacobian.row(0).transpose();
  const double mu = -grad_f.dot(grad_g) / grad_g.squaredNorm();
  EXPECT_GT(mu, 0.0);
  EXPECT_LE((grad_f + mu * grad_g).norm(), 1e-4 * grad_f.norm());
  EXPECT_NEAR(r.x[0], 0.7864, 1e-4);  // the published optimum (MATLAB's fmincon example), to its digits
  EXPECT_NEAR(r.x[1], 0.6177, 1e-4);
}

// The figures of the design variables against iterations need each record's point: evaluated
// independently, it has the record's cost. Ipopt 3.11 does not hand its iterate to the callback;
// the adapter finds it among the points just evaluated, by its cost.
TEST_P(EveryOptimizer, RecordsEachIterateWithItsCost) {
  test::RosenbrockInDisc problem;
  const OptimizerResult r = minimize(GetParam(), problem, tightOptions());
  ASSERT_GE(r.history.size(), 2u);
  for (const IterationRecord& record : r.history) {
    ASSERT_EQ(record.x.size(), 2) << "iteration " << record.iteration;
    NlpEvaluation e;
    problem.evaluate(record.x, false, e);
    EXPECT_NEAR(e.cost, record.cost, 1e-14 * std::max(1.0, std::abs(record.cost))) << "iteration " << record.iteration;
  }
  EXPECT_EQ(r.history.front().x, problem.start());
}

TEST_P(EveryOptimizer, SolvesHockSchittkowski71OrSaysWhyNot) {
  test::HockSchittkowski71 problem;
  const OptimizerResult r = minimize(GetParam(), problem, tightOptions());
  if (!optimizerInfo(GetParam()).takes_equalities) {  // NLopt's MMA and CCSAQ: inequalities only
    EXPECT_EQ(r.status, OptimizerStatus::Unsupported);
    EXPECT_NE(r.message.find("inequality constraints only"), std::string::npos) << r.message;
    EXPECT_EQ(r.value_evaluations, 0);
    return;
  }
  EXPECT_EQ(r.status, OptimizerStatus::Converged) << r.message;
  EXPECT_NEAR(r.cost, test::HockSchittkowski71::kOptimalCost, 1e-6);
  EXPECT_LE((r.x - test::HockSchittkowski71::optimum()).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LE(r.max_violation, 1e-8);
}

/// x ≥ 2 on [0, 1]: no feasible point exists.
class Infeasible : public NlpProblem {
 public:
  Eigen::Index variableCount() const override { return 1; }
  Eigen::Index inequalityCount() const override { return 1; }
  Eigen::VectorXd lowerBounds() const override { return Eigen::VectorXd::Zero(1); }
  Eigen::VectorXd upperBounds() const override { return Eigen::VectorXd::Ones(1); }
  Eigen::VectorXd start() const override { return Eigen::VectorXd::Constant(1, 0.5); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    out.cost = x[0] * x[0];
    out.constraints = Eigen::VectorXd::Constant(1, 2.0 - x[0]);
    if (gradients) {
      out.cost_gradient = Eigen::VectorXd::Constant(1, 2.0 * x[0]);
      out.constraint_jacobian = Eigen::MatrixXd::Constant(1, 1, -1.0);
    }
  }
};

TEST_P(EveryOptimizer, NeverCallsAnInfeasiblePointConverged) {
  Infeasible problem;
  OptimizerOptions options = tightOptions();
  options.max_iterations = 200;
  const OptimizerResult r = minimize(GetParam(), problem, options);
  EXPECT_NE(r.status, OptimizerStatus::Converged) << r.message;
  EXPECT_GE(r.max_violation, 1.0 - 1e-9);  // the best it can do is x = 1
}

/// min x subject to ⟨1 − x⟩² ≤ 0 on [0, 3] from x = 2: the paper's kind of constraint, exactly zero
/// with a zero gradient on the whole feasible set x ≥ 1. The optimum is x = 1.
class FlatConstraint : public NlpProblem {
 public:
  Eigen::Index variableCount() const override { return 1; }
  Eigen::Index inequalityCount() const override { return 1; }
  Eigen::VectorXd lowerBounds() const override { return Eigen::VectorXd::Zero(1); }
  Eigen::VectorXd upperBounds() const override { return Eigen::VectorXd::Constant(1, 3.0); }
  Eigen::VectorXd start() const override { return Eigen::VectorXd::Constant(1, 2.0); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    const double excess = std::max(1.0 - x[0], 0.0);
    out.cost = x[0];
    out.constraints = Eigen::VectorXd::Constant(1, excess * excess);
    if (gradients) {
      out.cost_gradient = Eigen::VectorXd::Ones(1);
      out.constraint_jacobian = Eigen::MatrixXd::Constant(1, 1, -2.0 * excess);
    }
  }
};

// Whoever stops short of x = 1 (MMA and CCSAQ treat a constraint at zero as active and cannot
// move) must not call it converged: the first-order check catches it (cost gradient 1, nothing to
// balance it, residual 1). Whoever calls it converged is at x = 1 within the feasibility tolerance
// of ⟨1 − x⟩² ≤ 1e-8, i.e. |x − 1| ≤ 1e-4.
TEST_P(EveryOptimizer, NeverCallsAPointItCannotLeaveConverged) {
  FlatConstraint problem;
  const OptimizerResult r = minimize(GetParam(), problem, tightOptions());
  if (r.status == OptimizerStatus::Converged) {
    EXPECT_NEAR(r.x[0], 1.0, 1e-4) << r.message;
  } else {
    EXPECT_GT(r.x[0], 1.0 - 1e-4) << r.message;  // never infeasible beyond the tolerance
  }
}

/// The quadratic, remembering every point it is evaluated at and failing beyond x₀ = 0.9.
/// A problem that records every call the optimizer makes: the point and whether it asked for gradients.
template <class Problem>
class Recording : public Problem {
 public:
  std::vector<std::pair<Eigen::VectorXd, bool>> calls;
  bool fail_beyond = false;
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    calls.emplace_back(x, gradients);
    if (fail_beyond && x[0] > 0.9) throw std::runtime_error("simulation diverged at x0 = " + std::to_string(x[0]));
    Problem::evaluate(x, gradients, out);
  }
};

std::vector<double> asKey(const Eigen::VectorXd& x) { return {x.data(), x.data() + x.size()}; }

// Every point's values are computed once and its gradients at most once (a design problem reuses
// the point's simulation for them), never values again after gradients; the counts are of points.
TEST_P(EveryOptimizer, EvaluatesNoPointTwice) {
  Recording<test::BoundedQuadratic> problem;
  const OptimizerResult r = minimize(GetParam(), problem, tightOptions());
  std::set<std::vector<double>> points, with_gradients;
  for (const auto& [x, gradients] : problem.calls) {
    EXPECT_FALSE(with_gradients.count(asKey(x))) << "asked again at a point whose gradients it has";
    if (gradients) with_gradients.insert(asKey(x));
    else EXPECT_TRUE(points.insert(asKey(x)).second) << "asked twice for the values of one point";
    points.insert(asKey(x));
  }
  EXPECT_EQ(r.value_evaluations, static_cast<long>(points.size()));
  EXPECT_EQ(r.gradient_evaluations, static_cast<long>(with_gradients.size()));
}

// SDCC needs a gradient only where it linearises, at the points it accepts (the history); a
// rejected trial point costs its values alone. On Rosenbrock's valley it rejects trials.
TEST(Optimizers, SdccAsksForGradientsOnlyAtThePointsItAccepts) {
  Recording<test::RosenbrockInDisc> problem;
  const OptimizerResult r = minimize("sdcc", problem, tightOptions());
  std::set<std::vector<double>> accepted;
  for (const IterationRecord& h : r.history) accepted.insert(asKey(h.x));
  long rejected = 0;
  for (const auto& [x, gradients] : problem.calls) {
    if (gradients) EXPECT_TRUE(accepted.count(asKey(x))) << "a gradient at a point SDCC did not accept";
    else if (!accepted.count(asKey(x))) ++rejected;
  }
  EXPECT_GT(rejected, 0);
  EXPECT_EQ(r.gradient_evaluations, static_cast<long>(accepted.size()));
}

TEST_P(EveryOptimizer, ReportsAFailedEvaluationWithItsReason) {
  Recording<test::BoundedQuadratic> problem;
  problem.fail_beyond = true;
  OptimizerOptions options = tightOptions();
  options.max_iterations = 100;
  const OptimizerResult r = minimize(GetParam(), problem, options);
  // NLopt stops at the failure; Ipopt and SDCC (which shrinks ξ) shorten their steps and keep
  // pressing against x₀ = 0.9.
  if (r.status != OptimizerStatus::Converged) {
    EXPECT_NE(r.message.find("simulation diverged"), std::string::npos) << r.message;
  }
  EXPECT_LE(r.x[0], 0.9);  // the best point is one that was evaluated successfully
}

/// A problem whose gradient costs 2.5 simulation-equivalents (an exact method's measured figure).
template <class Problem>
class CostlyGradients : public Recording<Problem> {
 public:
  double gradientCost() const override { return 2.5; }
};

/// A problem that takes 20 ms an evaluation.
template <class Problem>
class Slow : public Recording<Problem> {
 public:
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    Recording<Problem>::evaluate(x, gradients, out);
  }
};

// The common budget stops every algorithm alike: no evaluation takes a run beyond it, its count is
// the problem's own calls (1 for a new point's values, 2.5 for a gradient), the status and message
// say why, and every record lies within it. Unbounded, every algorithm needs more (checked first).
TEST_P(EveryOptimizer, StopsWithinItsBudgetOfSimulationEquivalents) {
  const double budget = 12.0, gradient_cost = 2.5;
  CostlyGradients<test::RosenbrockInDisc> unbounded;
  ASSERT_GT(minimize(GetParam(), unbounded, tightOptions()).simulation_equivalents, budget);
  CostlyGradients<test::RosenbrockInDisc> problem;
  OptimizerOptions options = tightOptions();
  options.budget.simulation_equivalents = budget;
  const OptimizerResult r = minimize(GetParam(), problem, options);
  EXPECT_EQ(r.status, OptimizerStatus::MaxIterations) << r.message;
  EXPECT_NE(r.message.find("the budget of 12 simulation-equivalents is spent"), std::string::npos) << r.message;
  double spent = 0.0;
  std::set<std::vector<double>> evaluated;
  for (const auto& [x, gradients] : problem.calls) {
    const bool known = !evaluated.insert(asKey(x)).second;
    spent += (known && gradients ? 0.0 : 1.0) + (gradients ? gradient_cost : 0.0);
  }
  EXPECT_LE(spent, budget);
  EXPECT_GT(spent, budget - 1.0 - gradient_cost);  // it stopped when the next evaluation did not fit
  EXPECT_DOUBLE_EQ(r.simulation_equivalents, spent);
  for (const IterationRecord& h : r.history) EXPECT_LE(h.simulation_equivalents, budget);
  EXPECT_EQ(r.x.size(), 2);  // the best point within the budget
}

// The wall-time budget: no evaluation starts after 0.1 s, and each takes at least 20 ms, so at most
// five are made (at 0, 20, 40, 60 and 80 ms at the earliest), where the run unbounded makes more.
TEST_P(EveryOptimizer, StartsNoEvaluationAfterItsWallTime) {
  Recording<test::RosenbrockInDisc> unbounded;
  minimize(GetParam(), unbounded, tightOptions());
  ASSERT_GT(unbounded.calls.size(), 5u);
  Slow<test::RosenbrockInDisc> problem;
  OptimizerOptions options = tightOptions();
  options.budget.wall_time_s = 0.1;
  const OptimizerResult r = minimize(GetParam(), problem, options);
  EXPECT_EQ(r.status, OptimizerStatus::MaxIterations) << r.message;
  EXPECT_NE(r.message.find("the budget of 0.1 s wall time is spent"), std::string::npos) << r.message;
  EXPECT_LE(problem.calls.size(), 5u);
}

INSTANTIATE_TEST_SUITE_P(Optimizers, EveryOptimizer, testing::ValuesIn(optimizerNames()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

// Settings by name reach the algorithm: a budget of 3 iterations set through Ipopt's own max_iter
// (the common budget says 1000) stops it after 3.
TEST(Optimizers, IpoptTakesItsOwnOptionsByName) {
  test::RosenbrockInDisc problem;
  OptimizerOptions options = tightOptions();
  options.settings = {{"max_iter", "3"}, {"mu_strategy", "adaptive"}};
  const OptimizerResult r = minimize("ipopt", problem, options);
  EXPECT_EQ(r.status, OptimizerStatus::MaxIterations) << r.message;
  EXPECT_EQ(r.iterations, 4);  // the start and three iterations
}

// NLopt's stopping criteria by NLopt's own names reach SLSQP, MMA and CCSAQ: stopval = 1e10, which the
// start's f already meets, stops them at their first evaluation; a loose xtol_rel or ftol_rel stops
// them sooner than the tight default on Rosenbrock's valley, which takes them dozens of evaluations.
// An MMA parameter is still refused by SLSQP.
TEST(Optimizers, NloptTakesItsStoppingCriteriaByTheirNames) {
  for (const std::string optimizer : {"slsqp", "mma", "ccsaq"}) {
    SCOPED_TRACE(optimizer);
    const auto evaluations = [&](const NamedSettings& settings) {
      test::RosenbrockInDisc problem;
      OptimizerOptions options = tightOptions();
      options.settings = settings;
      return minimize(optimizer, problem, options).value_evaluations;
    };
    const long tight = evaluations({});
    ASSERT_GT(tight, 10);
    EXPECT_EQ(evaluations({{"stopval", "1e10"}}), 1);
    EXPECT_LT(evaluations({{"xtol_rel", "1e-2"}}), tight);
    EXPECT_LT(evaluations({{"ftol_rel", "1e-2"}, {"xtol_abs", "0"}, {"ftol_abs", "0"}, {"maxtime", "0"}}), tight);
  }
  test::BoundedQuadratic problem;
  OptimizerOptions options = tightOptions();
  options.settings = {{"inner_maxeval", "5"}};
  EXPECT_THROW(minimize("slsqp", problem, options), std::invalid_argument);
}

TEST_P(EveryOptimizer, RefusesASettingItDoesNotKnowBeforeEvaluatingAnything) {
  Recording<test::BoundedQuadratic> problem;
  OptimizerOptions options = tightOptions();
  options.settings = {{"no_such_setting", "1"}};
  EXPECT_THROW(minimize(GetParam(), problem, options), std::invalid_argument);
  EXPECT_TRUE(problem.calls.empty());
}

// A Latin hypercube: every point in the box, and each of the count equal strata of every variable
// holding exactly one point; the same seed gives the same points, another seed other points.
TEST(LatinHypercube, PutsOnePointInEveryStratumOfEveryVariable) {
  const Eigen::VectorXd lower = test::values({-1.0, 0.0, 1e3}), upper = test::values({1.0, 0.5, 5e4});
  const int count = 7;
  const std::vector<Eigen::VectorXd> points = latinHypercube(lower, upper, count, 42);
  ASSERT_EQ(points.size(), 7u);
  for (Eigen::Index j = 0; j < lower.size(); ++j) {
    std::set<int> strata;
    for (const Eigen::VectorXd& p : points) {
      EXPECT_GE(p[j], lower[j]);
      EXPECT_LE(p[j], upper[j]);
      strata.insert(static_cast<int>(std::floor(count * (p[j] - lower[j]) / (upper[j] - lower[j]))));
    }
    EXPECT_EQ(strata.size(), 7u) << "variable " << j;
  }
  const std::vector<Eigen::VectorXd> again = latinHypercube(lower, upper, count, 42), other = latinHypercube(lower, upper, count, 43);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_EQ(points[k], again[k]);
    EXPECT_NE(points[k], other[k]);
  }
  EXPECT_THROW(latinHypercube(lower, test::values({1.0, 0.5, INFINITY}), count, 1), std::invalid_argument);
}

TEST(Optimizers, AnUnknownNameIsAnErrorThatListsTheKnownOnes) {
  test::BoundedQuadratic problem;
  try {
    minimize("bfgs", problem, {});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("slsqp"), std::string::npos);
  }
}

}  // namespace
}  // namespace mbsopt
