// Forward-AD passes over a chosen list of inputs of the residual f(q, q̇, q̈, λ; b) or of the
// kinematics: only the columns a caller keeps are seeded (free coordinates, design parameters),
// kMaxAdDirections of them per pass, every other input a constant.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <functional>
#include <initializer_list>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/scalar.hpp"
#include "mbsopt/model/workspace.hpp"

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

/// With ws's parameter seeds set, the driven coordinates whose motion reads a seeded parameter get
/// their q, q̇, q̈ at time t with the derivatives in it (their values those the integrator prescribed,
/// to the bit); seedAdPass calls it when ws.driving_model is set.
void seedDrivenMotions(const Model& model, Workspace<AdScalar>& ws, double t);

/// Seeds the pass over inputs [first, first + count): input first + j carries the unit derivative
/// direction j in ws.seeded_q, seeded_v, seeded_a (parameters through ws.parameter_seeds,
/// `parameters` being their indices in the model), every other input a constant; then, when
/// ws.driving_model is set, the driven motions (seedDrivenMotions at ws.driving_time).
SeededState seedAdPass(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                       const std::vector<AdInput>& inputs, const std::vector<ParameterIndex>& parameters,
                       Eigen::Index first, Eigen::Index count);

/// Runs `evaluate` once per pass of at most kMaxAdDirections inputs (seedAdPass);
/// evaluate(state, first, count) reads the derivatives it needs. Leaves no parameter seeded. A
/// template over the callable, so that no closure is copied (a std::function copies one of more
/// than two references to the heap, at every point of a gradient).
template <class Evaluate>
void forEachAdPass(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                   const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                   const std::vector<AdInput>& inputs, const std::vector<ParameterIndex>& parameters,
                   Evaluate&& evaluate) {
  const auto total = static_cast<Eigen::Index>(inputs.size());
  for (Eigen::Index first = 0; first < total; first += kMaxAdDirections) {
    const Eigen::Index count = std::min<Eigen::Index>(kMaxAdDirections, total - first);
    evaluate(seedAdPass(ws, q, v, a, inputs, parameters, first, count), first, count);
  }
  ws.parameter_seeds.clear();
}

/// ∂g/∂(inputs) of g = evaluate(state) (`rows` entries, evaluate writing them into its second
/// argument) at (q, q̇, q̈): one column per input, into `out` (reusing its storage).
void adJacobian(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                const std::vector<AdInput>& inputs, const std::vector<ParameterIndex>& parameters, Eigen::Index rows,
                const std::function<void(const SeededState&, VectorX<AdScalar>&)>& evaluate, Eigen::MatrixXd& out);

/// ∂f/∂(inputs) at (q, q̇, q̈, λ, t): coordinateCount() rows, one column per input. The state is
/// the one given, driven coordinates included, unless ws.driving_model is set (seedAdPass): a driven
/// motion's number then moves its joint too.
Eigen::MatrixXd residualJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                 double t, const std::vector<AdInput>& inputs,
                                 const std::vector<ParameterIndex>& parameters);

}  // namespace mbsopt
