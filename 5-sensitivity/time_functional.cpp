#include "mbsopt/sensitivity/time_functional.hpp"

#include <cmath>
#include <stdexcept>

namespace mbsopt {

Eigen::VectorXd trapezoidalWeights(const Eigen::VectorXd& time) {
  const Eigen::Index n = time.size();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const double half = 0.5 * (time[k + 1] - time[k]);
    w[k] += half;
    w[k + 1] += half;
  }
  return w;
}

TimeFunctionalValue evaluateTimeFunctional(TimeMeasure measure, const Eigen::VectorXd& time, const Eigen::VectorXd& g,
                                           double rho) {
  if (time.size() < 2 || g.size() != time.size())
    throw std::invalid_argument("time functional: needs at least two time points and one sample per point");
  if (!g.allFinite()) throw std::invalid_argument("time functional: the response is not finite");
  const Eigen::VectorXd w = trapezoidalWeights(time);
  TimeFunctionalValue out;
  out.gradient = Eigen::VectorXd::Zero(g.size());
  switch (measure) {
    case TimeMeasure::Integral:
      out.value = w.dot(g);
      out.gradient = w;
      break;
    case TimeMeasure::PositivePart: {
      const Eigen::VectorXd positive = g.cwiseMax(0.0);
      out.value = w.dot(positive);
      out.gradient = (g.array() > 0.0).select(w, 0.0);  // ⟨x⟩' = H(x), taken as 0 at x = 0
      break;
    }
    case TimeMeasure::SquaredPositivePart: {
      const Eigen::VectorXd positive = g.cwiseMax(0.0);
      out.value = w.dot(positive.cwiseAbs2());
      out.gradient = 2.0 * w.cwiseProduct(positive);
      break;
    }
    case TimeMeasure::KsAggregate: {
      if (!(rho > 0.0) || !std::isfinite(rho)) throw std::invalid_argument("time functional: KS needs rho > 0");
      // Shifted by max g so that no exponential overflows: KS = g_max + (1/ρ) ln(Σ w_k e^{ρ(g_k − g_max)} / T).
      const double top = g.maxCoeff();
      const Eigen::VectorXd e = w.cwiseProduct((rho * (g.array() - top)).exp().matrix());
      const double sum = e.sum();
      out.value = top + std::log(sum / (time[time.size() - 1] - time[0])) / rho;
      out.gradient = e / sum;
      break;
    }
    case TimeMeasure::GridMax: {
      Eigen::Index at = 0;
      out.value = g.maxCoeff(&at);
      out.gradient[at] = 1.0;
      break;
    }
    case TimeMeasure::FinalValue:
      out.value = g[g.size() - 1];
      out.gradient[g.size() - 1] = 1.0;
      break;
    case TimeMeasure::RootMeanSquare: {
      const double duration = time[time.size() - 1] - time[0];
      out.value = std::sqrt(w.dot(g.cwiseAbs2()) / duration);
      if (out.value > 0.0) out.gradient = w.cwiseProduct(g) / (duration * out.value);  // (0 where g ≡ 0)
      break;
    }
  }
  return out;
}

}  // namespace mbsopt
