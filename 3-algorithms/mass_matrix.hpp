// Mass matrix M = ∂f/∂q̈ (f is linear in q̈) by the Composite Rigid Body Algorithm: one backward
// sweep of composite inertias, then M(i, j) = S_jᵀ IC_i S_i along each joint's path to the ground.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

/// Needs ws to hold rotations, positions and joint axes at q (forwardKinematics at Velocity level or
/// above); reads ws only. M is coordinateCount() square.
void massMatrix(const Model& model, Workspace<double>& ws, Eigen::MatrixXd& M);
/// The block of M on `coordinates` (distinct; rows and columns in that order, e.g. the free
/// coordinates), computing only those entries. Same needs on ws.
void massMatrix(const Model& model, Workspace<double>& ws, const std::vector<int>& coordinates, Eigen::MatrixXd& M);

}  // namespace mbsopt
