#include "mbsopt/sensitivity/parameter_jacobian.hpp"

#include "mbsopt/sensitivity/forward_ad.hpp"

namespace mbsopt {

Eigen::MatrixXd parameterJacobian(const Model& model, Workspace<AdScalar>& ws, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& v, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                  double t, const std::vector<ParameterIndex>& parameters) {
  // The state is constant in these passes; only the parameters carry derivatives.
  return residualJacobian(model, ws, q, v, a, lambda, t, parameterInputs(parameters.size()), parameters);
}

}  // namespace mbsopt
