#include "mbsopt/sensitivity/forward_ad.hpp"

#include <algorithm>
#include <numeric>

#include "mbsopt/algorithms/residual.hpp"

namespace mbsopt {

std::vector<AdInput> adInputs(AdInput::Kind kind, const std::vector<int>& indices) {
  std::vector<AdInput> out;
  out.reserve(indices.size());
  for (int i : indices) out.push_back({kind, i});
  return out;
}

std::vector<AdInput> parameterInputs(std::size_t count) {
  std::vector<int> indices(count);
  std::iota(indices.begin(), indices.end(), 0);
  return adInputs(AdInput::Kind::Parameter, indices);
}

std::vector<AdInput> adInputs(std::initializer_list<std::vector<AdInput>> parts) {
  std::vector<AdInput> out;
  for (const std::vector<AdInput>& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

void seedDrivenMotions(const Model& model, Workspace<AdScalar>& ws, double t) {
  for (const int i : model.drivenCoordinates()) {
    const bool seeded = std::any_of(ws.parameter_seeds.begin(), ws.parameter_seeds.end(),
                                    [&](const auto& seed) { return drivingCoordinate(model, seed.first) == i; });
    if (!seeded) continue;
    const TimeInput& motion = model.coordinates()[static_cast<std::size_t>(i)].motion;
    ws.seeded_q[i] = timeValue(model, ws, motion, t, 0);
    ws.seeded_v[i] = timeValue(model, ws, motion, t, 1);
    ws.seeded_a[i] = timeValue(model, ws, motion, t, 2);
  }
}

SeededState seedAdPass(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                       const std::vector<AdInput>& inputs, const std::vector<ParameterIndex>& parameters,
                       Eigen::Index first, Eigen::Index count) {
  seedVector(q, 0, 0, 0, ws.seeded_q);
  seedVector(v, 0, 0, 0, ws.seeded_v);
  seedVector(a, 0, 0, 0, ws.seeded_a);
  ws.parameter_seeds.clear();
  for (Eigen::Index j = 0; j < count; ++j) {
    const AdInput& input = inputs[static_cast<std::size_t>(first + j)];
    const auto direction = static_cast<int>(j);
    switch (input.kind) {
      case AdInput::Kind::Position: ws.seeded_q[input.index].derivatives()[direction] = 1.0; break;
      case AdInput::Kind::Velocity: ws.seeded_v[input.index].derivatives()[direction] = 1.0; break;
      case AdInput::Kind::Acceleration: ws.seeded_a[input.index].derivatives()[direction] = 1.0; break;
      case AdInput::Kind::Parameter:
        ws.parameter_seeds.emplace_back(parameters[static_cast<std::size_t>(input.index)], direction);
        break;
    }
  }
  if (ws.driving_model && !ws.parameter_seeds.empty()) seedDrivenMotions(*ws.driving_model, ws, ws.driving_time);
  return SeededState{ws.seeded_q, ws.seeded_v, ws.seeded_a};
}

void adJacobian(Workspace<AdScalar>& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                const Eigen::Ref<const Eigen::VectorXd>& v, const Eigen::Ref<const Eigen::VectorXd>& a,
                const std::vector<AdInput>& inputs, const std::vector<ParameterIndex>& parameters, Eigen::Index rows,
                const std::function<void(const SeededState&, VectorX<AdScalar>&)>& evaluate, Eigen::MatrixXd& out) {
  out.resize(rows, static_cast<Eigen::Index>(inputs.size()));
  VectorX<AdScalar>& g = ws.seeded_f;
  forEachAdPass(ws, q, v, a, inputs, parameters, [&](const SeededState& s, Eigen::Index first, Eigen::Index count) {
    evaluate(s, g);
    for (Eigen::Index i = 0; i < rows; ++i) out.row(i).segment(first, count) = g[i].derivatives().head(count);
  });
}

Eigen::MatrixXd residualJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                 double t, const std::vector<AdInput>& inputs,
                                 const std::vector<ParameterIndex>& parameters) {
  seedVector(lambda, 0, 0, 0, ws.seeded_lambda);  // constant
  const VectorX<AdScalar>& lambda_ad = ws.seeded_lambda;
  Eigen::MatrixXd out;
  adJacobian(
      ws, q, v, a, inputs, parameters, model.coordinateCount(),
      [&](const SeededState& s, VectorX<AdScalar>& f) { residual(model, ws, s.q, s.v, s.a, lambda_ad, t, f); }, out);
  return out;
}

}  // namespace mbsopt
