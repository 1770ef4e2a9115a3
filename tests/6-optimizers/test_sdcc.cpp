// SDCC (paper §2.2, (6)-(11)) step by step: the projected steepest descent and the compensation on
// small linear constraints where every quantity has a closed form, the active-set rule of (11), and
// a run that compensates a violated linear constraint in its first step. The whole-run behaviour on
// the analytic problems is in test_optimizers.cpp (the EveryOptimizer suite).
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "mbsopt/optimizers/sdcc.hpp"
#include "tests/analytic_problems.hpp"

namespace mbsopt {
namespace {

using test::values;

/// Every quantity below is a handful of flops on O(1) numbers: round-off is ~1e-15, so 1e-12 only
/// fails if a formula is wrong.
constexpr double kRoundOff = 1e-12;

/// One constraint Ψ = value with gradient `gradient`, an inequality unless said otherwise.
ConstraintLinearization oneConstraint(double value, const Eigen::VectorXd& gradient, bool equality = false) {
  ConstraintLinearization c;
  c.values = Eigen::VectorXd::Constant(1, value);
  c.gradients = gradient;
  c.equality_count = equality ? 1 : 0;
  return c;
}

double wNorm(const Eigen::VectorXd& v, const Eigen::VectorXd& weights) {
  return std::sqrt(v.dot(weights.asDiagonal() * v));
}

// A violated linear constraint the cost pushes against (μ₁ > 0), with a non-identity W: the parts of
// the step are the projected steepest descent and the compensation, characterised by their defining
// properties rather than by the formulas the code uses.
TEST(Sdcc, TheStepIsTheWProjectedSteepestDescentPlusAWOrthogonalCompensation) {
  const Eigen::VectorXd weights = values({1.0, 4.0, 0.25});
  const Eigen::VectorXd cost_gradient = values({-1.0, -2.0, -3.0}), a = values({1.0, 1.0, 1.0});
  const double psi = 0.3, xi = 2.0;
  const SdccStep s = sdccStep(cost_gradient, oneConstraint(psi, a), weights, 0.01, xi);
  ASSERT_EQ(s.active.size(), 1U);
  ASSERT_EQ(s.multipliers.size(), 1);
  EXPECT_GT(s.multipliers[0], 0.0);
  // δb₁ is tangent to the constraint and solves l₀ + l̃μ₁ + Wδb₁ = 0 (11) with γ = ½: it is the
  // minimiser of l₀ᵀd + ½dᵀWd on the tangent plane, the W-projected steepest descent.
  EXPECT_NEAR(a.dot(s.descent), 0.0, kRoundOff);
  EXPECT_LE((cost_gradient + a * s.multipliers[0] + weights.asDiagonal() * s.descent).norm(), kRoundOff);
  EXPECT_LT(cost_gradient.dot(s.descent), 0.0);
  // δb₂ zeroes the linearized constraint (9) and is W-orthogonal to δb₁, so (10) splits exactly.
  EXPECT_NEAR(a.dot(s.compensation), -psi, kRoundOff);
  EXPECT_NEAR(s.descent.dot(weights.asDiagonal() * s.compensation), 0.0, kRoundOff);
  ASSERT_LT(wNorm(s.compensation, weights), xi);  // so the compensation is taken whole
  EXPECT_EQ(s.scale_compensation, 1.0);
  EXPECT_NEAR(wNorm(s.step, weights), xi, kRoundOff);
  EXPECT_NEAR(a.dot(s.step), -psi, kRoundOff);
}

// When the compensation alone is longer than ξ, no γ ≥ 0 satisfies (10)-(11): the step is the
// compensation shortened to ξ, with no descent in it.
TEST(Sdcc, ACompensationLongerThanTheStepBoundIsShortenedToIt) {
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones(2);
  const SdccStep s = sdccStep(values({-1.0, 0.0}), oneConstraint(3.0, values({1.0, 0.0})), weights, 0.01, 0.5);
  EXPECT_EQ(s.scale_descent, 0.0);
  EXPECT_NEAR(s.scale_compensation, 0.5 / 3.0, kRoundOff);
  EXPECT_LE((s.step - values({-0.5, 0.0})).norm(), kRoundOff);
}

// x₀ ≤ 0 active at x₀ = 0 (Ψ = 0). Descent along −l₀ = (−1, −1) enters the feasible side, so
// μ₁ = −aᵀl₀/aᵀa = −1 < 0 and the constraint leaves the set: the step is plain steepest descent (6).
// With l₀ = (−1, 1) the cost pushes outward, μ₁ = 1 > 0, and the step slides along x₀ = 0.
TEST(Sdcc, AnInequalityWithANegativeMultiplierLeavesTheActiveSet) {
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones(2), a = values({1.0, 0.0});
  const double xi = 0.1;
  const SdccStep inward = sdccStep(values({1.0, 1.0}), oneConstraint(0.0, a), weights, 0.01, xi);
  EXPECT_TRUE(inward.active.empty());
  EXPECT_LE((inward.step + xi * values({1.0, 1.0}) / std::sqrt(2.0)).norm(), kRoundOff);

  const SdccStep outward = sdccStep(values({-1.0, 1.0}), oneConstraint(0.0, a), weights, 0.01, xi);
  ASSERT_EQ(outward.active.size(), 1U);
  EXPECT_NEAR(outward.multipliers[0], 1.0, kRoundOff);
  EXPECT_LE((outward.step - values({0.0, -xi})).norm(), kRoundOff);
}

TEST(Sdcc, AnEqualityNeverLeavesTheActiveSet) {
  const SdccStep s =
      sdccStep(values({1.0, 1.0}), oneConstraint(0.0, values({1.0, 0.0}), true), Eigen::VectorXd::Ones(2), 0.01, 0.1);
  ASSERT_EQ(s.active.size(), 1U);
  EXPECT_NEAR(s.multipliers[0], -1.0, kRoundOff);
  EXPECT_NEAR(s.step[0], 0.0, kRoundOff);
}

// The ε of (7): an inequality at −2ε is left out of the set, one at −ε/2 is in it.
TEST(Sdcc, OnlyInequalitiesWithinEpsilonOfZeroAreActive) {
  const Eigen::VectorXd cost_gradient = values({-1.0, 1.0}), a = values({1.0, 0.0});
  const double epsilon = 0.01, xi = 1.0;
  EXPECT_TRUE(sdccStep(cost_gradient, oneConstraint(-2 * epsilon, a), Eigen::VectorXd::Ones(2), epsilon, xi).active.empty());
  EXPECT_EQ(sdccStep(cost_gradient, oneConstraint(-epsilon / 2, a), Eigen::VectorXd::Ones(2), epsilon, xi).active.size(), 1U);
}

// The same constraint twice (rank-deficient LᵀW⁻¹L): the rank-revealing solve still gives the
// projection onto the one tangent direction and the compensation, with nothing undefined.
TEST(Sdcc, DependentActiveConstraintsGiveAFiniteProjection) {
  ConstraintLinearization c;
  c.values = values({0.2, 0.2});
  c.gradients.resize(2, 2);
  c.gradients << 1.0, 1.0, 1.0, 1.0;
  const SdccStep s = sdccStep(values({-1.0, -2.0}), c, Eigen::VectorXd::Ones(2), 0.01, 1.0);
  ASSERT_TRUE(s.step.allFinite());
  ASSERT_TRUE(s.multipliers.allFinite());
  EXPECT_NEAR(values({1.0, 1.0}).dot(s.descent), 0.0, kRoundOff);
  EXPECT_NEAR(values({1.0, 1.0}).dot(s.compensation), -0.2, kRoundOff);
}

/// The situation of problems/suite/quarter_car.yaml where SDCC failed: the variables (k, c, b) with k
/// and c at their lower bounds, b free; the cost is b; the epigraph (cost functional − b ≤ 0) holds,
/// and two constraints on k and c alone are violated (the travel's maximum and minimum), each mended
/// by raising k or c. Taken as equalities of the projection (11), the two bounds outnumbered the
/// variables beside the violated constraints, and the least-squares compensation did not move:
/// every trial predicted nothing and ξ shrank to its floor. A bound now holds its variable only
/// where the step would cross it, so the compensation mends both constraints by leaving the bounds.
TEST(Sdcc, TheCompensationMayLeaveAVariablesBound) {
  ConstraintLinearization c;
  c.values = values({0.0, 0.0049, 0.0068, -4.5, -4.7, -9.6, 0.0, 0.0, -0.37});
  c.gradients.resize(3, 9);
  c.gradients << 0.081, 0.0001, -0.0006, 1, 0, 0, -1, 0, 0,  //
      0.207, -0.0165, -0.0070, 0, 1, 0, 0, -1, 0,            //
      -1, 0, 0, 0, 0, 1, 0, 0, -1;
  c.equality_count = 0;
  c.bound_count = 6;
  const SdccStep s = sdccStep(values({0.0, 0.0, 1.0}), c, Eigen::VectorXd::Ones(3), 0.01, 10.0);
  // The least-norm compensation would lower k a little (it eases the maximum's constraint): k's
  // bound holds it there; c's does not hold c, which the compensation raises.
  EXPECT_EQ(std::count(s.active.begin(), s.active.end(), 6), 1);
  EXPECT_EQ(std::count(s.active.begin(), s.active.end(), 7), 0);
  const Eigen::VectorXd after = c.values + c.gradients.transpose() * s.step;
  EXPECT_LE(after.head(3).maxCoeff(), kRoundOff);  // the linearized constraints are met
  EXPECT_LE(after.tail(6).maxCoeff(), kRoundOff);  // inside the bounds
  EXPECT_GT(s.step[1], 0.0);                        // c rises off its bound
}

/// (x, b) with the cost b at a point where δb₁ vanishes: x is fixed by an equality, and both sides of
/// an extreme, a x − b ≤ 0 (violated by 0.002) and −a x − b ≤ 0 (met with 0.005 to spare, within ε),
/// are active. Three constraints for two variables: compensating all of them to zero is
/// inconsistent. The satisfied side, whose compensation multiplier μ₂ is negative, leaves, and the
/// step mends the violated one: δb = (0, 0.002) (problems/suite/train_couplers.yaml).
TEST(Sdcc, ASatisfiedInequalityLeavesACompensationThatCannotMeetThemAll) {
  ConstraintLinearization c;
  const double a = 0.5;
  c.values = values({0.0, 0.002, -0.005});
  c.gradients.resize(2, 3);
  c.gradients << 1.0, a, -a,  //
      0.0, -1.0, -1.0;
  c.equality_count = 1;
  const SdccStep s = sdccStep(values({0.0, 1.0}), c, Eigen::VectorXd::Ones(2), 0.01, 1.0);
  EXPECT_LE(s.descent.norm(), kRoundOff);
  EXPECT_NEAR(s.step[0], 0.0, kRoundOff);
  EXPECT_NEAR(s.step[1], 0.002, kRoundOff);
  EXPECT_EQ(std::count(s.active.begin(), s.active.end(), 2), 0);  // the satisfied side left
}

/// min (x₀ + 1)² + 2(x₁ + 1)² subject to x₀ + x₁ ≥ 1, from (0, 0) where the constraint is violated
/// by 1 and the cost pushes away from it (μ₁ = 3 > 0). The optimum is on x₀ + x₁ = 1, where
/// 2(x₀ + 1) = 4(x₁ + 1) gives (1, 0). Rosenbrock's class lends its two variables, one inequality,
/// bounds [−2, 2]² and start (0, 0); only the functions differ.
class QuadraticAboveALine : public test::RosenbrockInDisc {
 public:
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    out.cost = (x[0] + 1) * (x[0] + 1) + 2 * (x[1] + 1) * (x[1] + 1);
    out.constraints = Eigen::VectorXd::Constant(1, 1 - x[0] - x[1]);
    if (gradients) {
      out.cost_gradient = values({2 * (x[0] + 1), 4 * (x[1] + 1)});
      out.constraint_jacobian = values({-1, -1}).transpose();
    }
  }
};

// ξ₀ = 0.8 exceeds ‖δb₂‖ = 1/√2, so the first step compensates the linear constraint whole: the
// first accepted iterate is the first trial, and its violation is round-off of x₀ + x₁ ≈ 1.
TEST(Sdcc, CompensatesAViolatedLinearConstraintInOneStep) {
  QuadraticAboveALine problem;
  OptimizerOptions options;
  options.feasibility_tolerance = 1e-10;
  SdccSettings settings;
  settings.initial_step_bound = 0.8;
  const OptimizerResult r = minimizeWithSdcc(problem, options, settings);
  ASSERT_GE(r.history.size(), 2U);
  EXPECT_EQ(r.history[0].max_violation, 1.0);
  EXPECT_EQ(r.history[1].value_evaluations, 2);
  EXPECT_LE(r.history[1].max_violation, kRoundOff);
  EXPECT_EQ(r.status, OptimizerStatus::Converged) << r.message;
  // ‖δb₁‖ ≤ 1e-7 × ‖l₀(b₀)‖ ≈ 4.5e-7 at the end; f's curvature along the line is 3, so x is within
  // ~1.5e-7 of the optimum.
  EXPECT_NEAR(r.x[0], 1.0, 1e-6);
  EXPECT_NEAR(r.x[1], 0.0, 1e-6);
}

/// min b subject to |x| − b ≤ 0, (x, b) in [−1, 1]²: the optimum (0, 0) lies on the kink of the
/// constraint, as a grid maximum's optimum may. Away from x = 0 the constraint's gradient is
/// (sign x, −1), and ∇f + μ∇Ψ = (μ sign x, 1 − μ) never vanishes: no KKT point to certify.
class KinkedConstraint : public test::RosenbrockInDisc {
 public:
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    out.cost = x[1];
    out.constraints = Eigen::VectorXd::Constant(1, std::abs(x[0]) - x[1]);
    if (gradients) {
      out.cost_gradient = values({0, 1});
      out.constraint_jacobian = values({x[0] >= 0 ? 1.0 : -1.0, -1}).transpose();
    }
  }
  Eigen::VectorXd lowerBounds() const override { return values({-1, -1}); }
  Eigen::VectorXd upperBounds() const override { return values({1, 1}); }
  Eigen::VectorXd start() const override { return values({0.5, 1}); }
};

// Without a KKT point SDCC ends when no step longer than its floor, tolerance × max(1, ‖b‖_W),
// lowers the merit: at a feasible point within a few floors of the optimum. Before, it halved ξ
// down to 1e-10 (about 20 more evaluations) and reported "failed". The first-order check, which
// finds no multipliers either, still reports the point as no KKT point: the verdict is "failed",
// with both reasons.
TEST(Sdcc, WithoutAKktPointItStopsWhereNoStepAboveItsFloorLowersTheMerit) {
  KinkedConstraint problem;
  OptimizerOptions options;
  options.tolerance = 1e-6;
  options.max_iterations = 1000;
  const OptimizerResult r = minimizeWithSdcc(problem, options);
  EXPECT_NE(r.message.find("fell below 1e-06 (xtol_rel max(1, ‖b‖_W), at least 1e-10) at a feasible point"),
            std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("not first-order optimal"), std::string::npos) << r.message;
  EXPECT_EQ(r.status, OptimizerStatus::Failed);
  EXPECT_LE(r.max_violation, options.feasibility_tolerance);
  EXPECT_LE(r.x.cwiseAbs().maxCoeff(), 1e-5) << r.x.transpose();
}

/// min x₀ subject to x₀² + 1 ≤ 0: no feasible point at all.
class InfeasibleConstraint : public test::RosenbrockInDisc {
 public:
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    out.cost = x[0];
    out.constraints = Eigen::VectorXd::Constant(1, x[0] * x[0] + 1);
    if (gradients) {
      out.cost_gradient = values({1, 0});
      out.constraint_jacobian = values({2 * x[0], 0}).transpose();
    }
  }
};

// The same floor at an infeasible point ends the run as failed: the constraint is at its least
// violation, x₀ = 0, and no step lowers the merit.
TEST(Sdcc, ItFailsWhereTheStepBoundFallsBelowItsFloorAtAnInfeasiblePoint) {
  InfeasibleConstraint problem;
  OptimizerOptions options;
  options.max_iterations = 1000;
  const OptimizerResult r = minimizeWithSdcc(problem, options);
  EXPECT_EQ(r.status, OptimizerStatus::Failed) << r.message;
  EXPECT_NE(r.message.find("infeasible point"), std::string::npos) << r.message;
}

/// Rosenbrock's problem in the disc, recording every evaluation and every anticipated point.
class RecordingRosenbrock : public test::RosenbrockInDisc {
 public:
  struct Call {
    Eigen::VectorXd x;
    bool gradients;
    Eigen::VectorXd anticipated;  ///< the last point anticipated before this evaluation (empty if none)
  };
  std::vector<Call> calls;
  Eigen::VectorXd last_anticipated;
  int anticipations = 0;

  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    calls.push_back({x, gradients, last_anticipated});
    RosenbrockInDisc::evaluate(x, gradients, out);
  }
  void anticipate(const Eigen::VectorXd& x) override {
    last_anticipated = x;
    ++anticipations;
  }
};

// The hint SDCC gives before it evaluates a trial (NlpProblem::anticipate), once a trial from the
// same point has been rejected, must name the very point it evaluates next if this one is rejected
// too, to the bit: a problem that simulated the hint ahead of time would otherwise have simulated
// for nothing. A trial was rejected when its values are followed by another point's values rather
// than by its own gradients. ξ₀ = 4 on Rosenbrock's valley makes the first trials overshoot, so
// runs of rejections happen (checked).
TEST(Sdcc, AfterARejectionItEvaluatesThePointItAnticipated) {
  RecordingRosenbrock problem;
  SdccSettings settings;
  settings.initial_step_bound = 4.0;
  OptimizerOptions options;
  options.max_iterations = 200;
  minimizeWithSdcc(problem, options, settings);
  int second_rejections = 0;  // rejected trials that follow a rejected trial from the same point
  for (std::size_t i = 2; i + 1 < problem.calls.size(); ++i) {
    const auto& before = problem.calls[i - 1];
    const auto& trial = problem.calls[i];
    const auto& next = problem.calls[i + 1];
    if (before.gradients || trial.gradients || next.gradients) continue;
    ++second_rejections;
    ASSERT_EQ(trial.anticipated.size(), next.x.size()) << "trial " << i;
    EXPECT_EQ(trial.anticipated, next.x) << "trial " << i;
  }
  EXPECT_GE(second_rejections, 2);
  EXPECT_GE(problem.anticipations, second_rejections);
}

TEST(Sdcc, RefusesWeightsThatAreNotOnePositiveNumberPerVariable) {
  test::BoundedQuadratic problem;
  SdccSettings settings;
  settings.weights = values({1.0, 0.0});
  EXPECT_THROW(minimizeWithSdcc(problem, {}, settings), std::invalid_argument);
  settings.weights = values({1.0});
  EXPECT_THROW(minimizeWithSdcc(problem, {}, settings), std::invalid_argument);
}

TEST(Sdcc, ReadsItsSettingsByNameAndRefusesValuesOutOfRange) {
  const SdccSettings read = sdccSettings({{"initial_step_bound", "0.5"}, {"weights", "1,2.5"}, {"shrink_factor", "0.25"}});
  EXPECT_EQ(read.initial_step_bound, 0.5);
  EXPECT_EQ(read.shrink_factor, 0.25);
  EXPECT_EQ(read.weights, values({1.0, 2.5}));
  EXPECT_EQ(read.growth_factor, SdccSettings{}.growth_factor);  // the rest keep their defaults
  EXPECT_THROW(sdccSettings({{"weights", "1,x"}}), std::invalid_argument);
  EXPECT_THROW(sdccSettings({{"initial_step_bound", "0.5m"}}), std::invalid_argument);
  EXPECT_THROW(sdccSettings({{"shrink_factor", "1"}}), std::invalid_argument);  // ξ would never shrink
  EXPECT_THROW(sdccSettings({{"xi", "1"}}), std::invalid_argument);
}

}  // namespace
}  // namespace mbsopt
