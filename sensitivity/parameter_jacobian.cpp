#include "sensitivity/parameter_jacobian.hpp"

#include <algorithm>

#include "dynamics/residual.hpp"

namespace mbsopt {

Eigen::MatrixXd parameterJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                  double t, const std::vector<std::string>& parameters) {
  const auto p = static_cast<Eigen::Index>(parameters.size());
  Eigen::MatrixXd out(model.coordinateCount(), p);
  // The state is constant in these passes; only the parameters carry derivatives.
  const VectorX<AdScalar> q_ad = seededVector(q, 0, 0, 0), v_ad = seededVector(v, 0, 0, 0);
  const VectorX<AdScalar> a_ad = seededVector(a, 0, 0, 0), lambda_ad = seededVector(lambda, 0, 0, 0);
  VectorX<AdScalar> f;
  for (Eigen::Index first = 0; first < p; first += kMaxAdDirections) {
    const Eigen::Index count = std::min<Eigen::Index>(kMaxAdDirections, p - first);
    ws.parameter_seeds.clear();
    for (Eigen::Index j = 0; j < count; ++j)
      ws.parameter_seeds.emplace_back(&model.parameterReference(parameters[static_cast<std::size_t>(first + j)]),
                                      static_cast<int>(j));
    residual(model, ws, q_ad, v_ad, a_ad, lambda_ad, t, f);
    for (Eigen::Index i = 0; i < f.size(); ++i) out.row(i).segment(first, count) = f[i].derivatives().head(count);
  }
  ws.parameter_seeds.clear();
  return out;
}

}  // namespace mbsopt
