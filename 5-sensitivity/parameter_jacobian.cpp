#include "mbsopt/sensitivity/parameter_jacobian.hpp"

#include "mbsopt/sensitivity/forward_ad.hpp"

namespace mbsopt {

std::vector<ParameterIndex> parameterIndices(const Model& model, const std::vector<std::string>& parameters) {
  std::vector<ParameterIndex> out;
  out.reserve(parameters.size());
  for (const std::string& name : parameters) out.push_back(model.parameterIndex(name));
  return out;
}

Eigen::MatrixXd parameterJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                  double t, const std::vector<std::string>& parameters) {
  // The state is constant in these passes; only the parameters carry derivatives.
  return residualJacobian(model, ws, q, v, a, lambda, t, parameterInputs(parameters.size()),
                          parameterIndices(model, parameters));
}

}  // namespace mbsopt
