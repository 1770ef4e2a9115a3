#include "mbsopt/integrators/trajectory.hpp"

#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/sensors.hpp"

namespace mbsopt {

Eigen::MatrixXd sensorHistory(const Model& model, const Trajectory& trajectory) {
  Workspace<double> ws(model);
  const Eigen::Index points = trajectory.time.size();
  Eigen::MatrixXd out(points, static_cast<Eigen::Index>(model.sensors().size()));
  if (out.cols() == 0) return out;  // no sensors: a row of an empty matrix would offset a null pointer
  Eigen::VectorXd q, v, a, lambda;
  for (Eigen::Index k = 0; k < points; ++k) {
    q = trajectory.q.col(k);
    v = trajectory.v.col(k);
    a = trajectory.a.col(k);
    if (trajectory.lambda.rows() > 0) lambda = trajectory.lambda.col(k);
    forwardKinematics(model, ws, q, v, a, KinematicsLevel::Acceleration);
    sensorValues(model, ws, q, v, a, lambda, trajectory.time[k], out.row(k));
  }
  return out;
}

}  // namespace mbsopt
