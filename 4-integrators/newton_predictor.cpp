#include "mbsopt/integrators/newton_predictor.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mbsopt {

namespace {

/// The window, once the pair is known to make a least-squares fit.
int checkedWindow(int degree, int window) {
  if (degree < 0 || window <= degree)
    throw std::invalid_argument("NewtonPredictor: a polynomial of degree " + std::to_string(degree) +
                                " needs a window of more than " + std::to_string(degree) + " solutions, not " +
                                std::to_string(window));
  return window;
}

}  // namespace

std::vector<double> NewtonPredictor::extrapolationWeights(int degree, int window) {
  checkedWindow(degree, window);
  if (window == degree + 1) {  // the interpolating polynomial: wᵢ = (−1)ⁱ C(window, i + 1), exactly
    std::vector<double> weights(static_cast<std::size_t>(window));
    double binomial = window;  // C(window, 1)
    for (int i = 0; i < window; ++i) {
      weights[static_cast<std::size_t>(i)] = i % 2 == 0 ? binomial : -binomial;
      binomial = binomial * (window - i - 1) / (i + 2);
    }
    return weights;
  }
  // p(1) = φ(1)ᵀ c with c = V⁺ y the least-squares coefficients, V the Vandermonde matrix of the
  // sample times 0, −1, …, 1 − window: w = (V⁺)ᵀ φ(1). The times are scaled by 1/window, which keeps
  // V's condition number moderate (2.5e4 at degree 6 over 12).
  Eigen::MatrixXd vandermonde(window, degree + 1);
  Eigen::VectorXd ahead(degree + 1);
  const double scale = 1.0 / window;
  for (int p = 0; p <= degree; ++p) {
    ahead[p] = std::pow(scale, p);
    for (int i = 0; i < window; ++i) vandermonde(i, p) = std::pow(-i * scale, p);
  }
  const Eigen::VectorXd weights = vandermonde.completeOrthogonalDecomposition().pseudoInverse().transpose() * ahead;
  return {weights.data(), weights.data() + weights.size()};
}

NewtonPredictor::NewtonPredictor(Eigen::Index size, int degree, int window)
    : history_(size, checkedWindow(degree, window)) {
  // While the window fills: the exact extrapolation through the last min(known, 3) solutions (the
  // constant, linear and quadratic ones), zero weights on the older ones. weights_[0] is not used.
  weights_.resize(static_cast<std::size_t>(window) + 1);
  for (int known = 1; known < window; ++known) {
    const int used = std::min(known, 3);
    weights_[static_cast<std::size_t>(known)] = extrapolationWeights(used - 1, used);
    weights_[static_cast<std::size_t>(known)].resize(static_cast<std::size_t>(known), 0.0);
  }
  weights_[static_cast<std::size_t>(window)] = extrapolationWeights(degree, window);
}

bool NewtonPredictor::predict(Eigen::VectorXd& start) const {
  if (count_ == 0) return false;
  const std::vector<double>& weights = weights_[static_cast<std::size_t>(count_)];
  const int depth = static_cast<int>(history_.cols());
  start.setZero(history_.rows());
  for (int i = 0; i < count_; ++i) start += weights[static_cast<std::size_t>(i)] * history_.col((newest_ - i + depth) % depth);
  return true;
}

void NewtonPredictor::record(const Eigen::VectorXd& solution) {
  const int depth = static_cast<int>(history_.cols());
  newest_ = (newest_ + 1) % depth;
  history_.col(newest_) = solution;
  count_ = std::min(count_ + 1, depth);
}

}  // namespace mbsopt
