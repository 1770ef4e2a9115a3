// A scalar function of time with exact first and second derivatives: drivers, actuation,
// moving targets of guidance springs.
#pragma once

#include <utility>
#include <vector>

namespace mbsopt {

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
  static TimeFunction constant(double value) { return polynomial({value}); }
  static TimeFunction polynomial(std::vector<double> coefficients);
  static TimeFunction harmonic(double amplitude, double angular_frequency, double phase = 0.0, double offset = 0.0);

  double value(double t) const { return derivative(t, 0); }
  double rate(double t) const { return derivative(t, 1); }
  double acceleration(double t) const { return derivative(t, 2); }
  /// order-th derivative, order in {0, 1, 2}.
  double derivative(double t, int order) const;

  bool isConstant() const;

 private:
  std::vector<double> coefficients_{0.0};
  std::vector<Harmonic> harmonics_;
};

}  // namespace mbsopt
