// turnedAbout (2-model/scalar.hpp), the rotation of a revolute joint's exit frame, against Eigen's
// AngleAxis (an independent construction) for the coordinate axes its short path takes and for
// other axes, and its derivative in the angle by AD against the closed form d/dθ R_e R(θ) = R_e R(θ) [a]×.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "mbsopt/model/scalar.hpp"
#include "tests/random_matrices.hpp"

namespace mbsopt {
namespace {

using test_support::kEpsilon;

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d out;
  out << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return out;
}

TEST(TurnedAbout, EqualsTheAxisAngleRotationAndItsDerivative) {
  std::mt19937 generator(31);
  std::uniform_real_distribution<double> angle(-4.0, 4.0);
  const std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                             -Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1.0, 2.0, -2.0) / 3.0};
  for (const Eigen::Vector3d& axis : axes)
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::Matrix3d entry =
          Eigen::AngleAxisd(angle(generator), test_support::randomMatrix(3, 1, generator).normalized()).toRotationMatrix();
      const double theta = angle(generator);
      const Eigen::Matrix3d expected = entry * Eigen::AngleAxisd(theta, axis).toRotationMatrix();
      // Entries of rotation matrices, a few products each: a few ε.
      EXPECT_LT((turnedAbout(entry, axis, theta) - expected).cwiseAbs().maxCoeff(), 8 * kEpsilon) << axis.transpose();
      AdScalar seeded(theta, AdDerivatives::Unit(0));
      const Matrix3<AdScalar> turned = turnedAbout(Matrix3<AdScalar>(entry.cast<AdScalar>()), axis, seeded);
      const Eigen::Matrix3d derivative = expected * skew(axis);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(turned(r, c).value(), expected(r, c), 8 * kEpsilon);
          EXPECT_NEAR(turned(r, c).derivatives()[0], derivative(r, c), 8 * kEpsilon) << axis.transpose();
        }
    }
}

}  // namespace
}  // namespace mbsopt
