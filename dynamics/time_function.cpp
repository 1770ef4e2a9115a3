#include "dynamics/time_function.hpp"

#include <cmath>
#include <stdexcept>

namespace mbsopt {

TimeFunction TimeFunction::polynomial(std::vector<double> coefficients) { return {std::move(coefficients), {}}; }

TimeFunction TimeFunction::harmonic(double amplitude, double angular_frequency, double phase, double offset) {
  TimeFunction f = constant(offset);
  f.harmonics_.push_back({amplitude, angular_frequency, phase});
  return f;
}

double TimeFunction::derivative(double t, int order) const {
  if (order < 0 || order > 2) throw std::invalid_argument("TimeFunction: derivative order must be 0, 1 or 2");
  double sum = 0.0;
  // Horner on the differentiated polynomial.
  for (int k = static_cast<int>(coefficients_.size()) - 1; k >= order; --k) {
    double factor = 1.0;
    for (int j = 0; j < order; ++j) factor *= static_cast<double>(k - j);
    sum = sum * t + factor * coefficients_[static_cast<std::size_t>(k)];
  }
  for (const Harmonic& h : harmonics_) {
    const double phase = h.angular_frequency * t + h.phase;
    const double w = h.angular_frequency;
    switch (order) {
      case 0: sum += h.amplitude * std::sin(phase); break;
      case 1: sum += h.amplitude * w * std::cos(phase); break;
      default: sum -= h.amplitude * w * w * std::sin(phase); break;
    }
  }
  return sum;
}

bool TimeFunction::isConstant() const { return coefficients_.size() <= 1 && harmonics_.empty(); }

}  // namespace mbsopt
