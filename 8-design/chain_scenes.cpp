#include "mbsopt/design/chain_scenes.hpp"

#include <cmath>
#include <string>

namespace mbsopt {

Scene planarChainScene(int links) {
  constexpr double kLength = 0.5, kMass = 2.0, kInertia = kMass * kLength * kLength / 12.0;
  Scene scene;
  Model& m = scene.model;
  m.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
  FrameIndex tip = Model::ground;
  for (int i = 0; i < links; ++i) {
    const std::string joint = "joint" + std::to_string(i);
    const FrameIndex link = m.addRevolute(joint, tip, Eigen::Vector3d::UnitZ());
    m.addBody("link" + std::to_string(i), link, kMass, Eigen::Vector3d(0.5 * kLength, 0.0, 0.0),
              kInertia * Eigen::Matrix3d::Identity());
    m.addJointSpringDamper(joint + "_spring", joint, 50.0, 0.5);
    tip = m.addOffset("tip" + std::to_string(i), link, Eigen::Vector3d(kLength, 0.0, 0.0));
  }
  scene.q0 = Eigen::VectorXd::Constant(m.coordinateCount(), 0.3);
  scene.v0 = Eigen::VectorXd::Zero(m.coordinateCount());
  scene.settings.step = 1e-3;
  scene.settings.end_time = 1.0;
  return scene;
}

Scene closedPlanarChainScene(int links) {
  Scene scene = planarChainScene(links);
  Model& m = scene.model;
  scene.q0.setConstant(2.0 / links);
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  double heading = 0.0;
  for (int i = 0; i < links; ++i) {
    heading += scene.q0[i];
    tip += 0.5 * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0);
  }
  const FrameIndex anchor = m.addOffset("anchor", Model::ground, tip);
  m.addSphericalCut("pin", anchor, m.frame("tip" + std::to_string(links - 1)));
  return scene;
}

}  // namespace mbsopt
