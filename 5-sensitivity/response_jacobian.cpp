#include "mbsopt/sensitivity/response_jacobian.hpp"

#include <stdexcept>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/sensitivity/forward_ad.hpp"

namespace mbsopt {

void responseJacobians(const Model& model, Workspace<AdScalar>& ws, const std::vector<const Sensor*>& sensors,
                       const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                       const Eigen::Ref<const Eigen::VectorXd>& a, const std::vector<int>& columns,
                       std::vector<ResponseJacobian>& out, const std::vector<ParameterIndex>& parameters,
                       const Eigen::VectorXd* lambda) {
  const auto nc = static_cast<Eigen::Index>(columns.size());
  out.resize(sensors.size());
  for (ResponseJacobian& J : out) {
    J.position.resize(nc);
    J.velocity.resize(nc);
    J.acceleration.resize(nc);
    J.parameters.resize(static_cast<Eigen::Index>(parameters.size()));
  }
  for (const ParameterIndex p : parameters)
    if (drivingCoordinate(model, p) >= 0 && !ws.driving_model)
      throw std::logic_error("responseJacobians: a driven motion's number needs ws.driving_model and the time");
  // λ is a constant of every pass: the sensors that read it are linear in it (multiplierDerivatives).
  VectorX<AdScalar> constant_lambda;
  if (lambda) seedVector(*lambda, 0, 0, 0, constant_lambda);
  // Inputs ordered (q, q̇, q̈) on `columns`, then the parameters; one kinematics evaluation per pass
  // serves every sensor.
  const std::vector<AdInput> inputs =
      adInputs({adInputs(AdInput::Kind::Position, columns), adInputs(AdInput::Kind::Velocity, columns),
                adInputs(AdInput::Kind::Acceleration, columns), parameterInputs(parameters.size())});
  forEachAdPass(ws, q, v, a, inputs, parameters, [&](const SeededState& s, Eigen::Index first, Eigen::Index count) {
    forwardKinematics(model, ws, s.q, s.v, s.a, KinematicsLevel::Acceleration);
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      const bool reaction = readsMultipliers(*sensors[i]);
      if (reaction && !lambda)
        throw std::invalid_argument("responseJacobians: sensor '" + sensors[i]->name + "' needs the multipliers λ");
      const AdScalar g = reaction ? sensorValue(model, *sensors[i], ws, s.q, s.v, s.a, constant_lambda)
                                  : sensorValue(*sensors[i], ws, s.q, s.v, s.a);
      if (first == 0) multiplierDerivatives(model, ws, *sensors[i], out[i]);
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

void multiplierDerivatives(const Model& model, const Workspace<AdScalar>& ws, const Sensor& sensor,
                           ResponseJacobian& J) {
  const auto* reaction = std::get_if<CutReactionSensor>(&sensor.kind);
  if (!reaction) {
    J.multipliers.resize(0);
    return;
  }
  VectorX<AdScalar> c;
  reactionCoefficients(model, ws, *reaction, c);
  J.multipliers.resize(c.size());
  for (Eigen::Index i = 0; i < c.size(); ++i) J.multipliers[i] = c[i].value();
}

ResponseJacobian responseJacobian(const Model& model, Workspace<AdScalar>& ws, const Sensor& sensor,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
  std::vector<ResponseJacobian> out;
  responseJacobians(model, ws, {&sensor}, q, v, a, allCoordinates(model), out);
  return out.front();
}

}  // namespace mbsopt
