// Derivatives of a response (a sensor) with respect to the state: the ∂g/∂q, ∂g/∂q̇, ∂g/∂q̈ that
// every gradient method needs, accelerations included (paper §5.3, (59)-(65)). Forward AD of the
// sensor's own kinematics, so exact to round-off.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/workspace.hpp"

namespace mbsopt {

struct ResponseJacobian {
  double value = 0.0;
  Eigen::RowVectorXd position;      ///< ∂g/∂q, every coordinate (driven ones included) or the requested ones
  Eigen::RowVectorXd velocity;      ///< ∂g/∂q̇
  Eigen::RowVectorXd acceleration;  ///< ∂g/∂q̈
  /// ∂g/∂b explicitly, at a fixed state, for the parameters asked for (an offset's translation moves
  /// the point a sensor reads; no other parameter enters a state sensor): empty when none was.
  Eigen::RowVectorXd parameters;
};

/// The value and the state derivatives of `sensor` at (q, q̇, q̈).
ResponseJacobian responseJacobian(const Model& model, Workspace<AdScalar>& ws, const Sensor& sensor,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a);

/// The same for several sensors at once, over the coordinates `columns` only (entry j of each row
/// is the derivative in coordinate columns[j]) and the model parameters `parameters`: one
/// kinematics evaluation per AD pass serves them all. Into `out`, one per sensor, reusing its storage.
void responseJacobians(const Model& model, Workspace<AdScalar>& ws, const std::vector<const Sensor*>& sensors,
                       const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                       const Eigen::Ref<const Eigen::VectorXd>& a, const std::vector<int>& columns,
                       std::vector<ResponseJacobian>& out, const std::vector<ParameterIndex>& parameters = {});

}  // namespace mbsopt
