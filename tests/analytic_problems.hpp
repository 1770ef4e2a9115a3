// Nonlinear programs with known optima, for the optimizer tests (NlpProblem with exact gradients).
#pragma once

#include <cmath>
#include <initializer_list>

#include "mbsopt/optimizers/nlp_problem.hpp"

namespace mbsopt::test {

/// A dynamic vector from its entries (no fixed-size temporaries: GCC 12 warns on their AVX-512
/// packet loads).
inline Eigen::VectorXd values(std::initializer_list<double> entries) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(entries.size()));
  Eigen::Index i = 0;
  for (const double e : entries) v[i++] = e;
  return v;
}

/// min (x₀ − 2)² + (x₁ − ½)² on [0, 1]²: the optimum (1, ½) has the bound x₀ ≤ 1 active, f* = 1.
class BoundedQuadratic : public NlpProblem {
 public:
  Eigen::Index variableCount() const override { return 2; }
  Eigen::Index inequalityCount() const override { return 0; }
  Eigen::VectorXd lowerBounds() const override { return values({0, 0}); }
  Eigen::VectorXd upperBounds() const override { return values({1, 1}); }
  Eigen::VectorXd start() const override { return values({0.2, 0.9}); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    const Eigen::VectorXd d = x - values({2, 0.5});
    out.cost = d.squaredNorm();
    out.constraints.resize(0);
    if (gradients) {
      out.cost_gradient = 2.0 * d;
      out.constraint_jacobian.resize(0, 2);
    }
  }
};

/// Rosenbrock's function inside the unit disc: min (1 − x)² + 100 (y − x²)² subject to
/// x² + y² ≤ 1, from (0, 0). The unconstrained minimum (1, 1) lies outside, so the disc is active
/// at the optimum; the KKT conditions ∇f = −μ ∇g, μ ≥ 0, g = 0 locate it, which the test checks
/// independently of any optimizer.
class RosenbrockInDisc : public NlpProblem {
 public:
  Eigen::Index variableCount() const override { return 2; }
  Eigen::Index inequalityCount() const override { return 1; }
  Eigen::VectorXd lowerBounds() const override { return values({-2, -2}); }
  Eigen::VectorXd upperBounds() const override { return values({2, 2}); }
  Eigen::VectorXd start() const override { return values({0, 0}); }
  void evaluate(const Eigen::VectorXd& v, bool gradients, NlpEvaluation& out) override {
    const double x = v[0], y = v[1];
    out.cost = (1 - x) * (1 - x) + 100 * (y - x * x) * (y - x * x);
    out.constraints = Eigen::VectorXd::Constant(1, x * x + y * y - 1);
    if (gradients) {
      out.cost_gradient = values({-2 * (1 - x) - 400 * x * (y - x * x), 200 * (y - x * x)});
      out.constraint_jacobian = values({2 * x, 2 * y}).transpose();
    }
  }
};

/// Hock & Schittkowski problem 71: min x₀x₃(x₀ + x₁ + x₂) + x₂ subject to x₀x₁x₂x₃ ≥ 25,
/// Σxᵢ² = 40, 1 ≤ x ≤ 5, from (1, 5, 5, 1). Known optimum f* = 17.0140173 at
/// (1, 4.7429994, 3.8211503, 1.3794082) (Hock & Schittkowski 1981; Ipopt's own example).
class HockSchittkowski71 : public NlpProblem {
 public:
  static constexpr double kOptimalCost = 17.0140173;
  static Eigen::VectorXd optimum() { return values({1.0, 4.7429994, 3.8211503, 1.3794082}); }

  Eigen::Index variableCount() const override { return 4; }
  Eigen::Index inequalityCount() const override { return 1; }
  Eigen::Index equalityCount() const override { return 1; }
  Eigen::VectorXd lowerBounds() const override { return Eigen::VectorXd::Constant(4, 1); }
  Eigen::VectorXd upperBounds() const override { return Eigen::VectorXd::Constant(4, 5); }
  Eigen::VectorXd start() const override { return values({1, 5, 5, 1}); }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override {
    out.cost = x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2];
    out.constraints = values({25 - x.prod(), x.squaredNorm() - 40});  // g ≤ 0, then h = 0
    if (gradients) {
      out.cost_gradient =
          values({x[3] * (2 * x[0] + x[1] + x[2]), x[0] * x[3], x[0] * x[3] + 1, x[0] * (x[0] + x[1] + x[2])});
      out.constraint_jacobian.resize(2, 4);
      out.constraint_jacobian.row(0) =
          -values({x[1] * x[2] * x[3], x[0] * x[2] * x[3], x[0] * x[1] * x[3], x[0] * x[1] * x[2]}).transpose();
      out.constraint_jacobian.row(1) = 2 * x.transpose();
    }
  }
};

}  // namespace mbsopt::test
