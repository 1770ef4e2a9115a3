// Newton's start (4-integrators/newton_predictor.hpp) against what a least-squares polynomial
// extrapolation is: it reproduces every polynomial of its degree exactly, whatever the window (the
// fit of a polynomial of that degree has zero residual), and no polynomial of a higher degree;
// before its window is full it extrapolates exactly through the solutions it knows (constant,
// linear, then quadratic), and a full ring keeps doing so after it wraps around.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/integrators/newton_predictor.hpp"
#include "mbsopt/design/chain_scenes.hpp"

namespace mbsopt {
namespace {

/// A vector-valued polynomial of the step index, p(k) = Σⱼ cⱼ (k/10)ʲ, one column of c per entry.
struct Polynomial {
  Eigen::MatrixXd coefficients;  ///< (degree + 1) × size

  Eigen::VectorXd operator()(double k) const {
    Eigen::VectorXd value = Eigen::VectorXd::Zero(coefficients.cols());
    for (Eigen::Index j = coefficients.rows(); j-- > 0;) value = value * (k / 10.0) + coefficients.row(j).transpose();
    return value;
  }
  /// Σⱼ |cⱼ| (|k|/10)ʲ per entry, the largest: the size of the terms a value sums, for round-off bounds.
  double magnitude(double k) const {
    double largest = 0.0;
    for (Eigen::Index e = 0; e < coefficients.cols(); ++e) {
      double sum = 0.0;
      for (Eigen::Index j = 0; j < coefficients.rows(); ++j) sum += std::abs(coefficients(j, e)) * std::pow(std::abs(k) / 10.0, j);
      largest = std::max(largest, sum);
    }
    return largest;
  }
};

Polynomial randomPolynomial(int degree, Eigen::Index size, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  Polynomial p{Eigen::MatrixXd(degree + 1, size)};
  for (Eigen::Index i = 0; i < p.coefficients.size(); ++i) p.coefficients(i) = coefficient(generator);
  return p;
}

/// The 2-norm condition number of the Vandermonde matrix of the sample times 0, −1/w, …, −(w−1)/w
/// (the scaled times the weights are computed from), by an SVD: the weights' relative error is at most
/// about it times ε.
double vandermondeCondition(int degree, int window) {
  Eigen::MatrixXd v(window, degree + 1);
  for (int i = 0; i < window; ++i)
    for (int p = 0; p <= degree; ++p) v(i, p) = std::pow(-static_cast<double>(i) / window, p);
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(v).singularValues();
  return s[0] / s[s.size() - 1];
}

/// |p(1) − Σᵢ wᵢ p(−i)|∞ and the round-off allowed for it: ε times 64 Σᵢ |wᵢ| |p(−i)| (the Horner
/// evaluations and the sum) plus κ(V) Σᵢ |p(−i)| (the weights' own error).
std::pair<double, double> extrapolationError(const std::vector<double>& weights, const Polynomial& p, double condition) {
  Eigen::VectorXd predicted = Eigen::VectorXd::Zero(p.coefficients.cols());
  double terms = p.magnitude(1.0), samples = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    predicted += weights[i] * p(-static_cast<double>(i));
    terms += std::abs(weights[i]) * p.magnitude(-static_cast<double>(i));
    samples += p.magnitude(-static_cast<double>(i));
  }
  return {(predicted - p(1.0)).cwiseAbs().maxCoeff(),
          std::numeric_limits<double>::epsilon() * (64.0 * terms + condition * samples)};
}

TEST(NewtonPredictor, WeightsReproduceThePolynomialsOfTheirDegreeAndNoHigherOne) {
  for (const auto& [degree, window] : {std::pair{0, 1}, {1, 2}, {2, 3}, {2, 5}, {3, 6}, {4, 10}, {6, 12}}) {
    const std::vector<double> weights = NewtonPredictor::extrapolationWeights(degree, window);
    ASSERT_EQ(weights.size(), static_cast<std::size_t>(window));
    const double condition = vandermondeCondition(degree, window);
    for (int d = 0; d <= degree; ++d) {
      const auto [error, allowed] = extrapolationError(weights, randomPolynomial(d, 3, 17u + d), condition);
      EXPECT_LE(error, allowed) << "degree " << degree << " over " << window << ", polynomial of degree " << d;
    }
    // (k/10)^(degree+1) alone: a least-squares fit of a lower degree leaves a residual, so the
    // prediction misses by at least a fraction of the last term's variation over the window.
    Polynomial power{Eigen::MatrixXd::Zero(degree + 2, 1)};
    power.coefficients(degree + 1, 0) = 1.0;
    const auto [error, allowed] = extrapolationError(weights, power, condition);
    EXPECT_GT(error, 1e3 * allowed) << "degree " << degree << " over " << window;
  }
}

TEST(NewtonPredictor, LeastSquaresWeightsAreTheClosedFormOnes) {
  // Worked by hand from the normal equations: the mean of the window (degree 0); the line through
  // (0, y₀), (−1, y₋₁), (−2, y₋₂) at 1, ȳ + 2·(y₀ − y₋₂)/2; the parabola through four samples at 1.
  // The weights come from a pseudo-inverse: within κ(V)·ε of these (κ below 30 at these sizes).
  const auto expectWeights = [](int degree, int window, const std::vector<double>& expected) {
    const std::vector<double> weights = NewtonPredictor::extrapolationWeights(degree, window);
    ASSERT_EQ(weights.size(), expected.size());
    const double allowed = 4.0 * vandermondeCondition(degree, window) * std::numeric_limits<double>::epsilon();
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_NEAR(weights[i], expected[i], allowed) << "degree " << degree << " over " << window << ", weight " << i;
  };
  for (int window = 2; window <= 5; ++window) expectWeights(0, window, std::vector<double>(static_cast<std::size_t>(window), 1.0 / window));
  expectWeights(1, 3, {4.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0});
  expectWeights(2, 4, {9.0 / 4.0, -3.0 / 4.0, -5.0 / 4.0, 3.0 / 4.0});
  EXPECT_THROW(NewtonPredictor::extrapolationWeights(3, 3), std::invalid_argument);
  EXPECT_THROW(NewtonPredictor(2, 6, 6), std::invalid_argument);
}

TEST(NewtonPredictor, InterpolatingWeightsAreTheBinomialExtrapolation) {
  // window = degree + 1: the polynomial through every sample, p(1) = Σᵢ (−1)ⁱ C(w, i + 1) y₋ᵢ, i.e. the
  // (w)-th difference of the sequence vanishing (3, −3, 1 for the quadratic).
  EXPECT_EQ(NewtonPredictor::extrapolationWeights(0, 1), (std::vector<double>{1.0}));
  EXPECT_EQ(NewtonPredictor::extrapolationWeights(1, 2), (std::vector<double>{2.0, -1.0}));
  EXPECT_EQ(NewtonPredictor::extrapolationWeights(2, 3), (std::vector<double>{3.0, -3.0, 1.0}));
  EXPECT_EQ(NewtonPredictor::extrapolationWeights(3, 4), (std::vector<double>{4.0, -6.0, 4.0, -1.0}));
}

TEST(NewtonPredictor, StartsExactThroughWhatItKnowsAndKeepsItsDegreeOnceTheRingWraps) {
  const int degree = 6, window = 12;
  NewtonPredictor predictor(2, degree, window);
  Eigen::VectorXd start;
  EXPECT_FALSE(predictor.predict(start));
  EXPECT_EQ(start.size(), 0);
  // A quadratic: predicted exactly from the third solution on (the constant, linear, then quadratic
  // extrapolations while the window fills), and by the degree-6 fit once twelve are known, ring
  // wrapped or not. A cubic is missed while the window fills (the quadratic extrapolation), and
  // predicted exactly by the fit. Round-off allowed: 64ε times the terms summed, Σᵢ |wᵢ| |p(k−1−i)|
  // ≤ 22 max|p| (Σ|w| of the degree-6 fit), plus the weights' own error, κ(V)·ε·12 max|p|.
  const double condition = vandermondeCondition(degree, window);
  const auto allowed = [&](const Polynomial& p, int k) {
    double largest = 0.0;
    for (int i = 0; i <= std::min(k, window); ++i) largest = std::max(largest, p.magnitude(k - i));
    return std::numeric_limits<double>::epsilon() * (64.0 * 22.0 + 12.0 * condition) * largest;
  };
  const Polynomial quadratic = randomPolynomial(2, 2, 5u);
  const Polynomial cubic = randomPolynomial(3, 2, 6u);
  NewtonPredictor for_cubic(2, degree, window);
  for (int k = 0; k < 3 * window; ++k) {
    if (k > 0) {
      ASSERT_TRUE(predictor.predict(start));
      const double error = (start - quadratic(k)).cwiseAbs().maxCoeff();
      if (k >= 3) EXPECT_LE(error, allowed(quadratic, k)) << "step " << k;
      else EXPECT_GT(error, allowed(quadratic, k)) << "step " << k << ": fewer than three solutions cannot fit a quadratic";
      ASSERT_TRUE(for_cubic.predict(start));
      const double cubic_error = (start - cubic(k)).cwiseAbs().maxCoeff();
      if (k >= window) EXPECT_LE(cubic_error, allowed(cubic, k)) << "step " << k;
      else EXPECT_GT(cubic_error, allowed(cubic, k)) << "step " << k << ": the window is not full";
    }
    predictor.record(quadratic(k));
    for_cubic.record(cubic(k));
  }
  // A degree-6 polynomial only once the window is full.
  predictor.reset();
  EXPECT_FALSE(predictor.predict(start));
  const Polynomial sextic = randomPolynomial(degree, 2, 9u);
  for (int k = 0; k < 3 * window; ++k) {
    if (k >= window) {
      ASSERT_TRUE(predictor.predict(start));
      EXPECT_LE((start - sextic(k)).cwiseAbs().maxCoeff(), allowed(sextic, k)) << "step " << k;
    }
    predictor.record(sextic(k));
  }
}

TEST(NewtonPredictor, TheOpenChainTakesFewerIterationsForTheSameMotion) {
  // Eight links, no loop: Newton's target is its tolerance and its start the degree-6 fit. The
  // quadratic start took 4.35 Newton iterations per step on this chain, the fit 2.42
  // (bench_dynamics, BM_ChainNewmarkStep/8); at most 3 says the fit is in use. The motion is that
  // of a run converged far tighter (tolerance 1e-13): every step's accelerations within its
  // tolerance 1e-10·(1 + |q̈|∞), positions and rates within that accumulated over the steps (as
  // tests/3-algorithms/test_articulated_mass.cpp bounds two runs that differ by round-off).
  const Scene scene = planarChainScene(8);
  const Trajectory run = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  NewmarkSettings tight = scene.settings;
  tight.newton_tolerance = 1e-13;
  const Trajectory reference = NewmarkIntegrator(scene.model, tight).simulate(scene.q0, scene.v0);
  const IntegratorStatistics& s = run.statistics;
  EXPECT_LE(static_cast<double>(s.newton_iterations), 3.0 * static_cast<double>(s.steps));
  const NewmarkSettings& n = scene.settings;
  const double per_step = n.newton_tolerance * (1.0 + reference.a.cwiseAbs().maxCoeff());
  const double steps = static_cast<double>(s.steps);
  EXPECT_LE((run.a - reference.a).cwiseAbs().maxCoeff(), 10.0 * per_step);
  EXPECT_LE((run.q - reference.q).cwiseAbs().maxCoeff(), 10.0 * steps * n.beta * n.step * n.step * per_step);
  EXPECT_LE((run.v - reference.v).cwiseAbs().maxCoeff(), 10.0 * steps * n.gamma * n.step * per_step);
}

}  // namespace
}  // namespace mbsopt
