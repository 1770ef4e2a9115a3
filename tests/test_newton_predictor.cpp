// Newton's start (dynamics/newton_predictor.hpp) against what a least-squares polynomial
// extrapolation is: it reproduces every polynomial of its degree exactly, whatever the window (the
// fit of a polynomial of that degree has zero residual), and no polynomial of a higher degree;
// before its window is full it extrapolates exactly through the solutions it knows (constant,
// linear, then quadratic), and a full ring keeps doing so after it wraps around.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "dynamics/newton_predictor.hpp"

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

/// |p(1) − Σᵢ wᵢ p(−i)|∞ and the round-off allowed for it: ε times Σᵢ |wᵢ| (the terms' size) times
/// 64 for the Horner evaluations and the sum.
std::pair<double, double> extrapolationError(const std::vector<double>& weights, const Polynomial& p) {
  Eigen::VectorXd predicted = Eigen::VectorXd::Zero(p.coefficients.cols());
  double terms = p.magnitude(1.0);
  for (std::size_t i = 0; i < weights.size(); ++i) {
    predicted += weights[i] * p(-static_cast<double>(i));
    terms += std::abs(weights[i]) * p.magnitude(-static_cast<double>(i));
  }
  return {(predicted - p(1.0)).cwiseAbs().maxCoeff(), 64.0 * std::numeric_limits<double>::epsilon() * terms};
}

TEST(NewtonPredictor, WeightsReproduceThePolynomialsOfTheirDegreeAndNoHigherOne) {
  for (const auto& [degree, window] : {std::pair{0, 1}, {1, 2}, {2, 3}, {2, 5}, {3, 6}, {4, 10}, {6, 12}}) {
    const std::vector<double> weights = NewtonPredictor::extrapolationWeights(degree, window);
    ASSERT_EQ(weights.size(), static_cast<std::size_t>(window));
    for (int d = 0; d <= degree; ++d) {
      const auto [error, allowed] = extrapolationError(weights, randomPolynomial(d, 3, 17u + d));
      EXPECT_LE(error, allowed) << "degree " << degree << " over " << window << ", polynomial of degree " << d;
    }
    // (k/10)^(degree+1) alone: a least-squares fit of a lower degree leaves a residual, so the
    // prediction misses by at least a fraction of the last term's variation over the window.
    Polynomial power{Eigen::MatrixXd::Zero(degree + 2, 1)};
    power.coefficients(degree + 1, 0) = 1.0;
    const auto [error, allowed] = extrapolationError(weights, power);
    EXPECT_GT(error, 1e3 * allowed) << "degree " << degree << " over " << window;
  }
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
  // A quadratic: predicted exactly from the third solution on (constant, linear, then quadratic fits
  // through the known ones), and by the degree-6 fit once twelve are known, ring wrapped or not.
  const Polynomial quadratic = randomPolynomial(2, 2, 5u);
  for (int k = 0; k < 3 * window; ++k) {
    if (k > 0) {
      ASSERT_TRUE(predictor.predict(start));
      const double error = (start - quadratic(k)).cwiseAbs().maxCoeff();
      const double allowed = 1e3 * std::numeric_limits<double>::epsilon() * quadratic.magnitude(k);
      if (k >= 3) EXPECT_LE(error, allowed) << "step " << k;
      else EXPECT_GT(error, allowed) << "step " << k << ": fewer than three solutions cannot fit a quadratic";
    }
    predictor.record(quadratic(k));
  }
  // A degree-6 polynomial only once the window is full.
  predictor.reset();
  EXPECT_FALSE(predictor.predict(start));
  const Polynomial sextic = randomPolynomial(degree, 2, 9u);
  for (int k = 0; k < 3 * window; ++k) {
    if (k >= window) {
      ASSERT_TRUE(predictor.predict(start));
      EXPECT_LE((start - sextic(k)).cwiseAbs().maxCoeff(), 1e4 * std::numeric_limits<double>::epsilon() * sextic.magnitude(k))
          << "step " << k;
    }
    predictor.record(sextic(k));
  }
}

}  // namespace
}  // namespace mbsopt
