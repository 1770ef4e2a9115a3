// Derivatives of a response (a sensor) with respect to the state: the ∂g/∂q, ∂g/∂q̇, ∂g/∂q̈ that
// every gradient method needs, accelerations included (paper §5.3, (59)-(65)). Forward AD of the
// sensor's own kinematics, so exact to round-off.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

struct ResponseJacobian {
  double value = 0.0;
  Eigen::RowVectorXd position;      ///< ∂g/∂q, every coordinate (driven ones included) or the requested ones
  Eigen::RowVectorXd velocity;      ///< ∂g/∂q̇
  Eigen::RowVectorXd acceleration;  ///< ∂g/∂q̈
  /// ∂g/∂b explicitly, at a fixed state, for the parameters asked for (an offset's translation moves
  /// the point a sensor reads; no other parameter enters a state sensor): empty when none was.
  Eigen::RowVectorXd parameters;
  /// ∂g/∂λ, one entry per closure equation, for a sensor that reads the multipliers (a cut reaction,
  /// g = c(q)·λ: these are c); empty for every other sensor.
  Eigen::RowVectorXd multipliers;
};

/// The value and the state derivatives of `sensor` at (q, q̇, q̈).
ResponseJacobian responseJacobian(const Model& model, Workspace<AdScalar>& ws, const Sensor& sensor,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a);

/// The same for several sensors at once, over the coordinates `columns` only (entry j of each row
/// is the derivative in coordinate columns[j]) and the model parameters `parameters`: one
/// kinematics evaluation per AD pass serves them all. Into `out`, one per sensor, reusing its storage.
/// A cut reaction (readsMultipliers) needs the multipliers λ of the state: `lambda`, else nullptr. A
/// driven motion's number among `parameters` needs ws.driving_model and ws.driving_time set to the
/// state's (TrajectoryDerivatives does); std::logic_error otherwise.
void responseJacobians(const Model& model, Workspace<AdScalar>& ws, const std::vector<const Sensor*>& sensors,
                       const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                       const Eigen::Ref<const Eigen::VectorXd>& a, const std::vector<int>& columns,
                       std::vector<ResponseJacobian>& out, const std::vector<ParameterIndex>& parameters = {},
                       const Eigen::VectorXd* lambda = nullptr);

/// ∂g/∂λ of `sensor` from the value of its AD evaluation's coefficients (reactionCoefficients) into
/// J.multipliers, or J.multipliers emptied for a sensor that does not read λ; ws holds the
/// kinematics of the state at Position level at least.
void multiplierDerivatives(const Model& model, const Workspace<AdScalar>& ws, const Sensor& sensor,
                           ResponseJacobian& J);

}  // namespace mbsopt
