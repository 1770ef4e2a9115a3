// A scalar function of time with exact first and second derivatives: drivers, actuation,
// moving targets of guidance springs.
#pragma once

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace mbsopt {

/// The order-th derivative (order in {0, 1, 2}) at t of Σ_k c_k t^k + Σ_j A_j sin(ω_j t + φ_j), for
/// coefficients and harmonics of any scalar: coefficient(k) gives c_k, harmonic(j, 0 | 1 | 2) gives
/// A_j, ω_j, φ_j. Horner on the differentiated polynomial. TimeFunction evaluates its numbers with it,
/// the residual a time input's model parameters (so that AD differentiates them).
template <class Scalar, class Coefficient, class Harmonic>
Scalar timeFunctionDerivative(std::size_t coefficients, Coefficient coefficient, std::size_t harmonics,
                              Harmonic harmonic, double t, int order) {
  using std::cos;
  using std::sin;
  if (order < 0 || order > 2) throw std::invalid_argument("TimeFunction: derivative order must be 0, 1 or 2");
  Scalar sum(0.0);
  for (int k = static_cast<int>(coefficients) - 1; k >= order; --k) {
    double factor = 1.0;
    for (int j = 0; j < order; ++j) factor *= static_cast<double>(k - j);
    sum = sum * t + factor * coefficient(static_cast<std::size_t>(k));
  }
  for (std::size_t j = 0; j < harmonics; ++j) {
    const Scalar amplitude = harmonic(j, 0), w = harmonic(j, 1);
    const Scalar phase = w * t + harmonic(j, 2);
    switch (order) {
      case 0: sum += amplitude * sin(phase); break;
      case 1: sum += amplitude * w * cos(phase); break;
      default: sum -= amplitude * w * w * sin(phase); break;
    }
  }
  return sum;
}

/// f(t) = Σ_k c_k t^k + Σ_j A_j sin(ω_j t + φ_j).
class TimeFunction {
 public:
  struct Harmonic {
    double amplitude = 0.0;
    double angular_frequency = 0.0;
    double phase = 0.0;
  };

  TimeFunction() = default;
  TimeFunction(std::vector<double> coefficients, std::vector<Harmonic> harmonics)
      : coefficients_(std::move(coefficients)), harmonics_(std::move(harmonics)) {
    if (coefficients_.empty()) coefficients_.push_back(0.0);
  }
  static TimeFunction constant(double value) {
    TimeFunction f = polynomial({value});
    f.number_ = true;
    return f;
  }
  static TimeFunction polynomial(std::vector<double> coefficients);
  static TimeFunction harmonic(double amplitude, double angular_frequency, double phase = 0.0, double offset = 0.0);

  double value(double t) const { return derivative(t, 0); }
  double rate(double t) const { return derivative(t, 1); }
  double acceleration(double t) const { return derivative(t, 2); }
  /// order-th derivative, order in {0, 1, 2}.
  double derivative(double t, int order) const;

  bool isConstant() const;
  /// Made by constant(): a single number, not a function that happens to be constant. A time input
  /// names its parameter after itself then, after the function's terms otherwise (Model::timeInput).
  bool isNumber() const { return number_; }
  const std::vector<double>& coefficients() const { return coefficients_; }
  const std::vector<Harmonic>& harmonics() const { return harmonics_; }

 private:
  std::vector<double> coefficients_{0.0};
  std::vector<Harmonic> harmonics_;
  bool number_ = false;
};

}  // namespace mbsopt
