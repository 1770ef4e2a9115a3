// ∂g/∂(q, q̇, q̈) of the tramway's responses by forward AD, against central differences of the
// sensors themselves, and against what a joint sensor must give exactly.
#include <gtest/gtest.h>

#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/sensitivity/response_jacobian.hpp"
#include "mbsopt/design/tramway.hpp"

namespace mbsopt {
namespace {

double sensorAt(const Model& model, const Sensor& sensor, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                const Eigen::VectorXd& a) {
  Workspace<double> ws(model);
  forwardKinematics(model, ws, q, v, a, KinematicsLevel::Acceleration);
  return sensorValue(sensor, ws, q, v, a);
}

// A state in the curve (t = 3 s), where every response moves. Central differences with δ = 1e-6
// carry an O(δ²) truncation and a 1e-16/δ round-off: 1e-8 of the largest derivative is far above
// both and far below any modelling error.
TEST(ResponseJacobian, TramwayResponsesMatchCentralDifferences) {
  Scene scene = tramwayScene(TramwayDesign{}, TramwayOptions{});
  scene.settings.end_time = 3.0;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const Eigen::Index last = trajectory.time.size() - 1;
  const Eigen::VectorXd q = trajectory.q.col(last), v = trajectory.v.col(last), a = trajectory.a.col(last);
  Workspace<AdScalar> ws(scene.model);
  for (const Sensor& sensor : scene.model.sensors()) {
    const ResponseJacobian J = responseJacobian(scene.model, ws, sensor, q, v, a);
    // The same formulas in AD and in double; the compiler may fuse multiply-adds differently in each.
    const double value = sensorAt(scene.model, sensor, q, v, a);
    EXPECT_NEAR(J.value, value, 1e-14 * std::max(1.0, std::abs(value))) << sensor.name;
    const double scale = std::max({J.position.cwiseAbs().maxCoeff(), J.velocity.cwiseAbs().maxCoeff(),
                                   J.acceleration.cwiseAbs().maxCoeff()});
    const double delta = 1e-6;
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      const auto difference = [&](int which) {
        Eigen::VectorXd x[3] = {q, v, a}, y[3] = {q, v, a};
        x[which][i] += delta;
        y[which][i] -= delta;
        return (sensorAt(scene.model, sensor, x[0], x[1], x[2]) - sensorAt(scene.model, sensor, y[0], y[1], y[2])) /
               (2.0 * delta);
      };
      EXPECT_NEAR(J.position[i], difference(0), 1e-8 * scale) << sensor.name << " ∂/∂q " << i;
      EXPECT_NEAR(J.velocity[i], difference(1), 1e-8 * scale) << sensor.name << " ∂/∂q̇ " << i;
      EXPECT_NEAR(J.acceleration[i], difference(2), 1e-8 * scale) << sensor.name << " ∂/∂q̈ " << i;
    }
  }
  // The lateral acceleration of the nose depends on the accelerations (paper §5.3).
  const ResponseJacobian a_lat = responseJacobian(scene.model, ws, scene.model.sensors()[0], q, v, a);
  EXPECT_GT(a_lat.acceleration.cwiseAbs().maxCoeff(), 1.0);
}

// A joint-acceleration sensor is q̈_i itself: its Jacobian is the unit row e_i, exactly.
TEST(ResponseJacobian, JointAccelerationSensorIsAUnitRow) {
  Model model;
  const FrameIndex arm = model.addRevolute("arm", Model::ground, Eigen::Vector3d::UnitZ());
  model.addBody("bob", model.addRevolute("elbow", arm, Eigen::Vector3d::UnitZ()), 1.0, Eigen::Vector3d::UnitX(),
                Eigen::Matrix3d::Identity());
  model.addSensor("elbow_acceleration", JointSensor{1, Derivative::Acceleration});
  Workspace<AdScalar> ws(model);
  const Eigen::VectorXd q = Eigen::Vector2d(0.3, -0.2), v = Eigen::Vector2d(1.0, 2.0), a = Eigen::Vector2d(-3.0, 4.0);
  const ResponseJacobian J = responseJacobian(model, ws, model.sensors()[0], q, v, a);
  EXPECT_EQ(J.value, 4.0);
  EXPECT_EQ(J.acceleration, Eigen::RowVector2d(0.0, 1.0));
  EXPECT_EQ(J.position.norm() + J.velocity.norm(), 0.0);
}

}  // namespace
}  // namespace mbsopt
