// Mass matrix M = ∂f/∂q̈ by unit-acceleration recursions: f is linear in q̈, so column j is the
// inverse dynamics with q̈ = e_j and every velocity, gravity and force term removed. Exact, O(n²).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/workspace.hpp"

namespace mbsopt {

/// Needs ws to hold rotations, positions and joint axes at q (forwardKinematics at Velocity level or
/// above). Overwrites the acceleration and wrench buffers of ws. M is coordinateCount() square.
void massMatrix(const Model& model, Workspace<double>& ws, Eigen::MatrixXd& M);
/// The block of M on `coordinates` (rows and columns in that order, e.g. the free coordinates),
/// computing only those columns. Same needs and effects on ws.
void massMatrix(const Model& model, Workspace<double>& ws, const std::vector<int>& coordinates, Eigen::MatrixXd& M);

}  // namespace mbsopt
