#include "mbsopt/model/time_function.hpp"

namespace mbsopt {

TimeFunction TimeFunction::polynomial(std::vector<double> coefficients) { return {std::move(coefficients), {}}; }

TimeFunction TimeFunction::harmonic(double amplitude, double angular_frequency, double phase, double offset) {
  TimeFunction f = polynomial({offset});
  f.harmonics_.push_back({amplitude, angular_frequency, phase});
  return f;
}

double TimeFunction::derivative(double t, int order) const {
  return timeFunctionDerivative<double>(
      coefficients_.size(), [&](std::size_t k) { return coefficients_[k]; }, harmonics_.size(),
      [&](std::size_t j, int which) {
        const Harmonic& h = harmonics_[j];
        return which == 0 ? h.amplitude : which == 1 ? h.angular_frequency : h.phase;
      },
      t, order);
}

bool TimeFunction::isConstant() const { return coefficients_.size() <= 1 && harmonics_.empty(); }

}  // namespace mbsopt
