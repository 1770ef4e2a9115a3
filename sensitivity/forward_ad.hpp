// Forward-AD passes over a chosen list of inputs of the residual f(q, q̇, q̈, λ; b) or of the
// kinematics: only the columns a caller keeps are seeded (free coordinates, design parameters),
// kMaxAdDirections of them per pass, every other input a constant.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <initializer_list>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/scalar.hpp"
#include "dynamics/workspace.hpp"

namespace mbsopt {

/// One seeded input: a coordinate of q, q̇ or q̈, or a model parameter.
struct AdInput {
  enum class Kind { Position, Velocity, Acceleration, Parameter } kind;
  int index;  ///< the coordinate, or the position in the caller's list of parameters
};

/// One input of `kind` per entry of `indices`, in that order.
std::vector<AdInput> adInputs(AdInput::Kind kind, const std::vector<int>& indices);
/// The parameters 0, …, count − 1 of the caller's list, in order.
std::vector<AdInput> parameterInputs(std::size_t count);
/// The concatenation of input lists, in order.
std::vector<AdInput> adInputs(std::initializer_list<std::vector<AdInput>> parts);

/// The state (q, q̇, q̈) of one forward-AD pass (its parameter seeds are in the workspace, the
/// vectors too: the workspace's seeded_q, seeded_v, seeded_a).
struct SeededState {
  const VectorX<AdScalar>& q;
  const VectorX<AdScalar>& v;
  const VectorX<AdScalar>& a;
};

/// Runs `evaluate` once per pass of at most kMaxAdDirections inputs: input first + j carries the
/// unit derivative direction j in the state handed to it (parameters through ws.parameter_seeds,
/// `parameters` being their indices in the model); evaluate(state, first, count) reads the
/// derivatives it needs. Leaves no parameter seeded. A caller on a hot path passes its closure as
/// std::cref(closure): a std::function copies a closure of more than two references to the heap.
void forEachAdPass(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                   const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                   const std::vector<AdInput>& inputs,
                   const std::vector<ParameterIndex>& parameters,
                   const std::function<void(const SeededState&, Eigen::Index, Eigen::Index)>& evaluate);

/// ∂g/∂(inputs) of g = evaluate(state) (`rows` entries, evaluate writing them into its second
/// argument) at (q, q̇, q̈): one column per input, into `out` (reusing its storage).
void adJacobian(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                const std::vector<AdInput>& inputs, const std::vector<ParameterIndex>& parameters, Eigen::Index rows,
                const std::function<void(const SeededState&, VectorX<AdScalar>&)>& evaluate, Eigen::MatrixXd& out);

/// ∂f/∂(inputs) at (q, q̇, q̈, λ, t): coordinateCount() rows, one column per input.
Eigen::MatrixXd residualJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                 double t, const std::vector<AdInput>& inputs,
                                 const std::vector<ParameterIndex>& parameters);

}  // namespace mbsopt
