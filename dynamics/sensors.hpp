// Outputs of a simulation ("sensors"): point kinematics in a chosen frame, joint coordinates and
// rates, relative angles between bodies. Templated so later layers can differentiate them.
#pragma once

#include "dynamics/kinematics.hpp"
#include "dynamics/newmark.hpp"

namespace mbsopt {

/// Value of one sensor; ws must hold forwardKinematics at Acceleration level for (q, v, a).
template <class Scalar>
Scalar sensorValue(const Sensor& sensor, const Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                   const VectorX<Scalar>& v, const VectorX<Scalar>& a);

/// Every sensor at every time point of a trajectory: rows = time points, columns = model sensors.
Eigen::MatrixXd sensorHistory(const Model& model, const Trajectory& trajectory);

extern template double sensorValue<double>(const Sensor&, const Workspace<double>&, const VectorX<double>&,
                                           const VectorX<double>&, const VectorX<double>&);
extern template AdScalar sensorValue<AdScalar>(const Sensor&, const Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                               const VectorX<AdScalar>&, const VectorX<AdScalar>&);

}  // namespace mbsopt
