// Residual of the equations of motion by forward then backward recursion (paper §4.2, (22)-(25),
// with the loop forces of (37)):  f(q̈, q̇, q, t) = M q̈ + h(q, q̇, t) − Q + Bᵀλ  for every coordinate.
#pragma once

#include "dynamics/kinematics.hpp"

namespace mbsopt {

/// q, v, a: all coordinates (driven ones included). lambda: constraintCount() multipliers (may be
/// empty when the model has no cut joint). f receives coordinateCount() rows.
template <class Scalar>
void residual(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& q, const VectorX<Scalar>& v,
              const VectorX<Scalar>& a, const VectorX<Scalar>& lambda, double t, VectorX<Scalar>& f);

extern template void residual<double>(const Model&, Workspace<double>&, const VectorX<double>&,
                                      const VectorX<double>&, const VectorX<double>&, const VectorX<double>&,
                                      double, VectorX<double>&);
extern template void residual<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                        const VectorX<AdScalar>&, double, VectorX<AdScalar>&);

}  // namespace mbsopt
