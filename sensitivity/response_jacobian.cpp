#include "sensitivity/response_jacobian.hpp"

#include "dynamics/kinematics.hpp"
#include "dynamics/sensors.hpp"
#include "sensitivity/forward_ad.hpp"

namespace mbsopt {

void responseJacobians(const Model& model, Workspace<AdScalar>& ws, const std::vector<const Sensor*>& sensors,
                       const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                       const Eigen::Ref<const Eigen::VectorXd>& a, const std::vector<int>& columns,
                       std::vector<ResponseJacobian>& out, const std::vector<ParameterIndex>& parameters) {
  const auto nc = static_cast<Eigen::Index>(columns.size());
  out.resize(sensors.size());
  for (ResponseJacobian& J : out) {
    J.position.resize(nc);
    J.velocity.resize(nc);
    J.acceleration.resize(nc);
    J.parameters.resize(static_cast<Eigen::Index>(parameters.size()));
  }
  // Inputs ordered (q, q̇, q̈) on `columns`, then the parameters; one kinematics evaluation per pass
  // serves every sensor.
  const std::vector<AdInput> inputs =
      adInputs({adInputs(AdInput::Kind::Position, columns), adInputs(AdInput::Kind::Velocity, columns),
                adInputs(AdInput::Kind::Acceleration, columns), parameterInputs(parameters.size())});
  forEachAdPass(ws, q, v, a, inputs, parameters, [&](const SeededState& s, Eigen::Index first, Eigen::Index count) {
    forwardKinematics(model, ws, s.q, s.v, s.a, KinematicsLevel::Acceleration);
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      const AdScalar g = sensorValue(*sensors[i], ws, s.q, s.v, s.a);
      out[i].value = g.value();
      for (Eigen::Index j = 0; j < count; ++j) {
        const Eigen::Index input = first + j;
        if (input < nc) out[i].position[input] = g.derivatives()[j];
        else if (input < 2 * nc) out[i].velocity[input - nc] = g.derivatives()[j];
        else if (input < 3 * nc) out[i].acceleration[input - 2 * nc] = g.derivatives()[j];
        else out[i].parameters[input - 3 * nc] = g.derivatives()[j];
      }
    }
  });
}

ResponseJacobian responseJacobian(const Model& model, Workspace<AdScalar>& ws, const Sensor& sensor,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
  std::vector<ResponseJacobian> out;
  responseJacobians(model, ws, {&sensor}, q, v, a, allCoordinates(model), out);
  return out.front();
}

}  // namespace mbsopt
