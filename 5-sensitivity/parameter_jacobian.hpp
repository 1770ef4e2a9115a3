// ∂f/∂b: the derivative of the residual f = M q̈ + h − Q + Bᵀλ (37) with respect to model
// parameters at one state, the ∂f/∂b of the paper's sensitivity equations (49)-(50). Forward AD of
// the residual itself, the parameters seeded through Workspace::parameter_seeds, so exact and
// always consistent with the dynamics.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

/// n × p, one column per parameter (every coordinate's row, driven ones included), at the given
/// state: the driven coordinates too are held, so a driven motion's number has a zero column here
/// (TrajectoryDerivatives moves them, Workspace::driving_model).
Eigen::MatrixXd parameterJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                  double t, const std::vector<ParameterIndex>& parameters);

}  // namespace mbsopt
