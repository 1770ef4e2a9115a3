// The independent first-order (KKT) check that overrules an optimizer's "converged"
// (6-optimizers/first_order_check.hpp): zero at known optima, the same whatever units the variables
// are in, and not fooled by a variable whose derivative is small only because its unit is.
#include <gtest/gtest.h>

#include "mbsopt/optimizers/evaluation_cache.hpp"
#include "mbsopt/optimizers/first_order_check.hpp"
#include "tests/analytic_problems.hpp"

namespace mbsopt {
namespace {

using test::values;

/// `inner` with its variables in other units: x = unit ∘ x'. Bounds, start and gradients follow.
class InOtherUnits : public NlpProblem {
 public:
  InOtherUnits(NlpProblem& inner, Eigen::VectorXd unit) : inner_(inner), unit_(std::move(unit)) {}
  Eigen::Index variableCount() const override { return inner_.variableCount(); }
  Eigen::Index inequalityCount() const override { return inner_.inequalityCount(); }
  Eigen::Index equalityCount() const override { return inner_.equalityCount(); }
  Eigen::VectorXd lowerBounds() const override { return inner_.lowerBounds().cwiseQuotient(unit_); }
  Eigen::VectorXd upperBounds() const override { return inner_.upperBounds().cwiseQuotient(unit_); }
  Eigen::VectorXd start() const override { return inner_.start().cwiseQuotient(unit_); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    inner_.evaluate(unit_.cwiseProduct(x), gradients, out);
    if (!gradients) return;
    out.cost_gradient = out.cost_gradient.cwiseProduct(unit_);
    out.constraint_jacobian = out.constraint_jacobian * unit_.asDiagonal();
  }

 private:
  NlpProblem& inner_;
  Eigen::VectorXd unit_;
};

/// The tram's shape in one design variable: min b subject to a(k) − b ≤ 0 with a(k) = 3 − k/1000,
/// k ∈ [0, 1000] (in kN, say), b ∈ [0, 10]. The optimum is k = 1000, b = 2; anywhere else on the
/// constraint the cost can still fall by (1000 − k)/1000 although ∂a/∂k is only 1e-3 per unit.
class SlowlyFallingMaximum : public NlpProblem {
 public:
  Eigen::Index variableCount() const override { return 2; }
  Eigen::Index inequalityCount() const override { return 1; }
  Eigen::VectorXd lowerBounds() const override { return values({0, 0}); }
  Eigen::VectorXd upperBounds() const override { return values({1000, 10}); }
  Eigen::VectorXd start() const override { return values({500, 3}); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    out.cost = x[1];
    out.constraints = values({3 - x[0] / 1000 - x[1]});
    if (gradients) {
      out.cost_gradient = values({0, 1});
      out.constraint_jacobian = values({-1e-3, -1}).transpose();
    }
  }
};

double residualAt(NlpProblem& problem, const Eigen::VectorXd& x, double active_tolerance) {
  NlpEvaluation at;
  problem.evaluate(x, true, at);
  return firstOrderCheck(problem, x, at, active_tolerance).residual;
}

TEST(FirstOrderCheck, VanishesAtThePublishedOptimumOfHockSchittkowski71) {
  test::HockSchittkowski71 problem;
  // The optimum is published to 8 digits, so its constraints hold to ~1e-6 and the multipliers
  // balance the gradients to about as much.
  EXPECT_LE(residualAt(problem, test::HockSchittkowski71::optimum(), 1e-4), 1e-5);
}

TEST(FirstOrderCheck, HasThePublishedMultipliersOfHockSchittkowski71) {
  // Ipopt's documented solution of hs071 (its Lagrangian f + λ·g with g₁ = x₁x₂x₃x₄ ≥ 25, g₂ = Σxᵢ² = 40):
  // λ = (−0.5522937, 0.1614686), z_L = (1.087871, ~0, ~0, ~0), z_U ≈ 0. Here g₁ is written 25 − Πx ≤ 0,
  // which turns λ₁'s sign. The published optimum has 8 digits, which leaves the multipliers good to
  // about 1e-6 relative.
  test::HockSchittkowski71 problem;
  const Eigen::VectorXd x = test::HockSchittkowski71::optimum();
  NlpEvaluation at;
  problem.evaluate(x, true, at);
  const FirstOrderCheck check = firstOrderCheck(problem, x, at, 1e-4);
  EXPECT_NEAR(check.multipliers.constraints[0], 0.5522937, 1e-5 * 0.5522937);
  EXPECT_NEAR(check.multipliers.constraints[1], 0.1614686, 1e-5 * 0.1614686);
  EXPECT_NEAR(check.multipliers.lower[0], 1.087871, 1e-5 * 1.087871);
  EXPECT_EQ(check.multipliers.lower.tail(3).cwiseAbs().maxCoeff(), 0.0);  // inactive bounds
  EXPECT_EQ(check.multipliers.upper.cwiseAbs().maxCoeff(), 0.0);
}

TEST(FirstOrderCheck, DoesNotDependOnTheUnitsOfTheVariables) {
  test::HockSchittkowski71 hs71;
  InOtherUnits hs71_rescaled(hs71, values({1e-3, 1.0, 1e3, 7.0}));
  const Eigen::VectorXd x = values({1.5, 4.0, 3.5, 2.0});  // not optimal: a residual of order 1
  const double residual = residualAt(hs71, x, 1e-4);
  EXPECT_GT(residual, 0.1);
  EXPECT_NEAR(residualAt(hs71_rescaled, x.cwiseQuotient(values({1e-3, 1.0, 1e3, 7.0})), 1e-4), residual, 1e-12);

  test::RosenbrockInDisc rosenbrock;
  InOtherUnits rosenbrock_rescaled(rosenbrock, values({1e-4, 1e2}));
  const Eigen::VectorXd y = values({0.6, 0.8});  // on the disc, not the KKT point
  EXPECT_NEAR(residualAt(rosenbrock_rescaled, y.cwiseQuotient(values({1e-4, 1e2})), 1e-6), residualAt(rosenbrock, y, 1e-6),
              1e-12);
}

TEST(FirstOrderCheck, SeesThroughASmallDerivativeThatOnlyItsUnitMakesSmall) {
  SlowlyFallingMaximum problem;
  // On the constraint at k = 500: per unit, ∇f + λ∇g = (−λ/1000, 1 − λ) is 1e-3 of ∇f at λ = 1,
  // which a tolerance of 1e-2 would pass. Per range D = (1000, 10): D∇f = (0, 10) and
  // D∇g = (−1, −10); least squares gives λ = 100/101 and a residual of (100/101)/10.
  EXPECT_NEAR(residualAt(problem, values({500, 2.5}), 1e-6), 100.0 / 101.0 / 10.0, 1e-12);
  EXPECT_GT(residualAt(problem, values({500, 2.5}), 1e-6), kFirstOrderTolerance);
  // At the optimum the bound k ≤ 1000 takes the rest: a KKT point.
  EXPECT_LE(residualAt(problem, values({1000, 2}), 1e-6), 1e-14);
}

}  // namespace
}  // namespace mbsopt
