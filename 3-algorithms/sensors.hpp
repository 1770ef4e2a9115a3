// Outputs of a simulation ("sensors"): point kinematics in a chosen frame, joint coordinates and
// rates, relative angles between bodies, the mechanical energy and the reactions of cut joints.
// The state sensors (functions of q, q̇, q̈ alone) are templated so later layers can differentiate them.
#pragma once

#include "mbsopt/algorithms/kinematics.hpp"

namespace mbsopt {

/// One time point's row of a sensor matrix (rows = time points, columns = sensors).
using SensorRow = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

/// Whether a sensor is a function of the state (q, q̇, q̈) alone, which sensorValue evaluates and the
/// design gradients differentiate. An energy sensor also depends on the model parameters (masses,
/// stiffnesses) directly, a cut-reaction sensor on the multipliers λ: sensorHistory evaluates them.
bool isStateSensor(const Sensor& sensor);

/// Whether a sensor reads the multipliers λ of the cuts: a cut reaction, y = c(q)·λ
/// (reactionCoefficients in 3-algorithms/closure.hpp).
bool readsMultipliers(const Sensor& sensor);

/// Value of one state sensor (isStateSensor); ws must hold forwardKinematics at Acceleration level
/// for (q, v, a). Throws std::invalid_argument for another sensor.
template <class Scalar>
Scalar sensorValue(const Sensor& sensor, const Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                   const VectorX<Scalar>& v, const VectorX<Scalar>& a);

/// Value of a state sensor or of a cut reaction (readsMultipliers) at (q, q̇, q̈, λ): ws as for the
/// other overload, λ with constraintCount() entries. Throws std::invalid_argument for an energy sensor.
template <class Scalar>
Scalar sensorValue(const Model& model, const Sensor& sensor, const Workspace<Scalar>& ws, const VectorX<Scalar>& q,
                   const VectorX<Scalar>& v, const VectorX<Scalar>& a, const VectorX<Scalar>& lambda);

/// Every sensor of the model at one state, one entry per sensor into `values`: ws must hold
/// forwardKinematics at Acceleration level for (q, v, a); λ and t serve the energy and cut-reaction
/// sensors.
void sensorValues(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                  const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double t, SensorRow values);


extern template double sensorValue<double>(const Sensor&, const Workspace<double>&, const VectorX<double>&,
                                           const VectorX<double>&, const VectorX<double>&);
extern template AdScalar sensorValue<AdScalar>(const Sensor&, const Workspace<AdScalar>&, const VectorX<AdScalar>&,
                                               const VectorX<AdScalar>&, const VectorX<AdScalar>&);
extern template double sensorValue<double>(const Model&, const Sensor&, const Workspace<double>&,
                                           const VectorX<double>&, const VectorX<double>&, const VectorX<double>&,
                                           const VectorX<double>&);
extern template AdScalar sensorValue<AdScalar>(const Model&, const Sensor&, const Workspace<AdScalar>&,
                                               const VectorX<AdScalar>&, const VectorX<AdScalar>&,
                                               const VectorX<AdScalar>&, const VectorX<AdScalar>&);

}  // namespace mbsopt
