// Bodies with a positive semi-definite inertia tensor (problems/scenes/README.md, "Bodies"): a
// slender rod (one principal moment zero) and a point mass (all three zero) are rigid bodies; the
// model is then regular as long as every joint moves some mass, and refused at the joint otherwise.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {
namespace {

Model armModel() {
  Model model;
  model.addRevolute("hinge", Model::ground, Eigen::Vector3d::UnitY());
  return model;
}

TEST(ZeroInertia, SemiDefiniteInertiaIsARigidBody) {
  Model model = armModel();
  const FrameIndex arm = model.frame("hinge");
  const Eigen::Vector3d com(0, 0, -1);
  // A slender rod along x (I₁ = 0, I₂ = I₃: the triangle inequality holds with equality), and the
  // same rod turned by an arbitrary rotation, whose eigenvalues then carry round-off of either sign.
  const Eigen::Matrix3d rod = Eigen::Vector3d(0.0, 0.1, 0.1).asDiagonal();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NO_THROW(model.addBody("rod", arm, 2.0, com, rod));
  EXPECT_NO_THROW(model.addBody("turned_rod", arm, 2.0, com, R * rod * R.transpose()));
  EXPECT_NO_THROW(model.addBody("point", arm, 1.0, com, Eigen::Matrix3d::Zero()));
  // Negative moments and moments no mass distribution has stay refused.
  EXPECT_THROW(model.addBody("negative", arm, 1.0, com, Eigen::Vector3d(-1e-3, 0.1, 0.1).asDiagonal().toDenseMatrix()),
               std::invalid_argument);
  EXPECT_THROW(model.addBody("triangle", arm, 1.0, com, Eigen::Vector3d(0.0, 0.1, 0.2).asDiagonal().toDenseMatrix()),
               std::invalid_argument);
  // setParameter applies the same checks: the rod's Iyy may not drop below Izz − Ixx = 0.1.
  EXPECT_NO_THROW(model.setParameter("point.Ixx", 0.0));
  EXPECT_THROW(model.setParameter("rod.Iyy", 0.05), std::invalid_argument);
  EXPECT_EQ(model.parameter("rod.Iyy"), 0.1);
  EXPECT_THROW(model.setParameter("point.Ixx", -1e-6), std::invalid_argument);
}

// A point mass m = 1 kg at L = 1 m from a revolute joint, every inertia zero: m L² θ̈ = −m g L sin θ.
// Released from rest at θ₀ = 0.1 rad, the Lindstedt–Poincaré solution is
//     θ(t) = θ₀ cos ω't + (θ₀³/192)(cos 3ω't − cos ω't) + O(θ₀⁵),   ω' = ω (1 − θ₀²/16),  ω = √(g/L),
// so θ₀ cos ω't is exact up to θ₀³/96 = 1.04e-5 rad (the next frequency correction, 11θ₀⁴/3072 ω t θ₀,
// adds 4e-7 rad over the 2 s run). The trapezoidal rule integrates a harmonic oscillator exactly
// but at the frequency ω_h = (2/h) atan(ω'h/2) (Hughes 2000, §9.3.2): comparing with
// θ₀ cos ω_h t leaves θ₀³/96 plus terms O((ωh)⁴) ≈ 1e-10. Bound: θ₀³/96 · 1.1 + 1e-6.
TEST(ZeroInertia, PointMassPendulumFollowsTheSmallAngleSolution) {
  const char* text =
      "settings: {step: 1.0e-3, end_time: 2.0}\n"
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: hinge, type: revolute, parent: ground, axis: [0, 1, 0], q0: 0.1}\n"
      "bodies:\n"
      "  - {name: bob, frame: hinge, mass: 1.0, com: [0, 0, -1], Ixx: 0, Iyy: 0, Izz: 0}\n";
  const LoadedScene loaded = loadScene({"point_pendulum.yaml", text});
  const Scene& scene = loaded.scene;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const double theta0 = 0.1, h = 1e-3;
  const double omega = std::sqrt(9.81) * (1.0 - theta0 * theta0 / 16.0);
  const double omega_h = 2.0 / h * std::atan(omega * h / 2.0);
  const double bound = 1.1 * std::pow(theta0, 3) / 96.0 + 1e-6;
  double worst = 0.0;
  for (Eigen::Index k = 0; k < trajectory.time.size(); ++k)
    worst = std::max(worst, std::abs(trajectory.q(0, k) - theta0 * std::cos(omega_h * trajectory.time[k])));
  EXPECT_LE(worst, bound);
  // The third harmonic is really there: the comparison is not looser than it needs to be.
  EXPECT_GE(worst, 0.5 * std::pow(theta0, 3) / 96.0);
}

// A point mass on the axis of its revolute joint: the mass matrix is zero on that joint. The loader
// computes the first accelerations and refuses the scene at the line of the joint.
TEST(ZeroInertia, PointMassOnItsJointAxisIsRefusedAtTheJoint) {
  const char* text =
      "gravity: [0, 0, -9.81]\n"
      "elements:\n"
      "  - {name: hinge, type: revolute, parent: ground, axis: [0, 1, 0], q0: 0.3}\n"
      "bodies:\n"
      "  - {name: bob, frame: hinge, mass: 1.0, com: [0, 0.5, 0], Ixx: 0, Iyy: 0, Izz: 0}\n";
  try {
    loadScene({"on_axis.yaml", text});
    FAIL() << "a point mass on its joint axis was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "on_axis.yaml");
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(e.reason().find("nothing resists a motion of 'hinge'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mbsopt
