// Exact tangent matrices of the residual (31): M = ∂f/∂q̈, C_T = ∂f/∂q̇, K_T = ∂f/∂q, and the
// constraint Jacobian B = ∂b/∂q (36), by forward-mode automatic differentiation of the same
// templated recursions that compute f and b. No finite differences.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/scalar.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

struct TangentMatrices {
  Eigen::MatrixXd mass;       ///< M   = ∂f/∂q̈
  Eigen::MatrixXd damping;    ///< C_T = ∂f/∂q̇
  Eigen::MatrixXd stiffness;  ///< K_T = ∂f/∂q, including the geometric stiffness of the loop forces Bᵀλ
  Eigen::VectorXd residual;   ///< f itself
};

/// All coordinates, driven ones included (rows and columns in model coordinate order).
void tangentMatrices(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double t, TangentMatrices& out);

/// b(q) and B = ∂b/∂q over all coordinates. Exact: ḃ is linear in q̇ and b has no explicit time
/// dependence besides the coordinates, so column j of B is ḃ(q, q̇ = e_j), from the unit-rate twists
/// of the cut frames alone (O(cut frames) per column after one kinematics pass). Leaves in ws the
/// geometry at q; its frame rates are not those of any state.
void constraintJacobian(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q, Eigen::VectorXd& b,
                        Eigen::MatrixXd& B);
/// The same with only the columns of `columns`, in that order (the integrator's free coordinates).
void constraintJacobian(const Model& model, Workspace<double>& ws, const Eigen::VectorXd& q,
                        const std::vector<int>& columns, Eigen::VectorXd& b, Eigen::MatrixXd& B);

}  // namespace mbsopt
