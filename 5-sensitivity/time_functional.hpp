// Time functionals: how a response history g(t_k) on the integrator's grid becomes one number
// (paper (12)-(19), docs/design.md §4), with its gradient with respect to every sample g_k, which each
// gradient method chains with ∂g/∂(q, q̇, q̈, b).
//
// Integrals use the trapezoidal rule on the time grid: the quadrature of the trapezoidal Newmark
// scheme (β = 1/4, γ = 1/2) itself, second order, and linear in the samples, so the gradients
// below are exact derivatives of the discrete functional.
#pragma once

#include <Eigen/Core>

namespace mbsopt {

enum class TimeMeasure {
  Integral,             ///< ∫ g dt
  PositivePart,         ///< ∫ ⟨g⟩ dt, ⟨x⟩ = max(x, 0): the paper's equivalent constraint (15)-(16)
  SquaredPositivePart,  ///< ∫ ⟨g⟩² dt: the same feasible set, continuously differentiable there
  KsAggregate,          ///< (1/ρ) ln((1/T) ∫ exp(ρ g) dt): smooth, ≤ max g, → max g as ρ → ∞
  GridMax,              ///< max_k g(t_k): the plain maximum over the grid (a subgradient)
  FinalValue,           ///< g(t_N)
  RootMeanSquare        ///< √((1/T) ∫ g² dt): the RMS over the run (a comfort cost on accelerations)
};

struct TimeFunctionalValue {
  double value = 0.0;
  Eigen::VectorXd gradient;  ///< ∂value/∂g_k, one entry per time point
};

/// `time`: the grid t_0 < … < t_N (at least two points); `g`: the samples. `rho` > 0 is the KS
/// sharpness, in 1/(units of g). The KS form uses the time mean rather than the sum over grid
/// points, so that it converges as the step shrinks instead of growing with the number of points.
TimeFunctionalValue evaluateTimeFunctional(TimeMeasure measure, const Eigen::VectorXd& time, const Eigen::VectorXd& g,
                                           double rho = 50.0);

/// Trapezoidal weights w with ∫ f dt ≈ Σ w_k f(t_k) on the grid.
Eigen::VectorXd trapezoidalWeights(const Eigen::VectorXd& time);

}  // namespace mbsopt
