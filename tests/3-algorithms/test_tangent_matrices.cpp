// Exact tangent matrices (AD) against central finite differences of the double-precision residual,
// and the constraint Jacobian against the closure equations at position, velocity and acceleration
// level, on a random spatial chain with a closed loop.
//
// Finite-difference accuracy (central differences, step h relative to the coordinate):
//   truncation  ≈ h²/6 · |f'''|      ≈ 1e-12 · (scale of f)      for h = 1e-6,
//   round-off   ≈ ε·|f| / h          ≈ 2e-16 / 1e-6 ≈ 2e-10 · |f|.
// The round-off scales with the differenced function, not with its derivative, so the tolerance is
// 1e-8 · max(‖reference matrix‖, ‖f‖) (max norms): a margin of ~50 over the estimate above for the
// conditioning of the sums in the recursions, while a genuinely missing term (a geometric
// stiffness, a gyroscopic coupling) is of the order of the matrix itself and fails by orders of
// magnitude. Observed with this seed: 2e-11 … 2e-9 relative.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/articulated_body.hpp"
#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/mass_matrix.hpp"
#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/algorithms/tangent.hpp"

namespace mbsopt {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRelativeStep = 1e-6;       // FD step relative to max(1, |x_j|), see the header comment
constexpr double kFdTolerance = 1e-8;        // relative to the norm of the reference matrix
constexpr double kIdentityTolerance = 1e-12;  // two evaluations of the same exact quantity, different order

/// Random numbers from the raw mt19937 output (fully specified by the standard), so the
/// sequence is the same with every standard library.
class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}

  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(engine_()) / 4294967296.0); }
  Eigen::Vector3d vector(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
  Eigen::VectorXd vector(Eigen::Index n, double lo, double hi) {
    Eigen::VectorXd x(n);
    for (Eigen::Index i = 0; i < n; ++i) x[i] = uniform(lo, hi);
    return x;
  }
  /// A unit vector with every component at least 0.15 in magnitude: never near a coordinate axis.
  Eigen::Vector3d obliqueAxis() {
    for (;;) {
      const Eigen::Vector3d u = vector(-1.0, 1.0);
      if (u.norm() > 0.2 && u.norm() < 1.0 && (u / u.norm()).cwiseAbs().minCoeff() > 0.15) return u.normalized();
    }
  }
  Eigen::Matrix3d rotation() { return Eigen::AngleAxisd(uniform(-kPi, kPi), obliqueAxis()).toRotationMatrix(); }
  /// The inertia of a uniform box with random sides in [0.2, 1] m about its centre, turned by a
  /// random rotation: a real rigid body's tensor, generally not diagonal in the frame's axes.
  Eigen::Matrix3d inertia(double mass) {
    const Eigen::Vector3d side = vector(0.2, 1.0), s2 = side.cwiseProduct(side);
    const Eigen::Vector3d principal = mass / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
    const Eigen::Matrix3d R = rotation();
    return R * principal.asDiagonal() * R.transpose();
  }

 private:
  std::mt19937 engine_;
};

/// Six bodies in one spatial chain, two joints each and a ball joint before the fourth body's (15
/// coordinates, so the AD of the 3n = 45 inputs of the residual needs several passes of
/// kMaxAdDirections): revolute and prismatic joints about random oblique axes behind offsets with
/// random rotations; bodies with offset centres of
/// mass and full inertia tensors; joint spring-dampers on every coordinate, a point spring-damper
/// between bodies 1 and 4, gravity in a random direction. The loop is closed by a spherical cut
/// between a point of the last body and a point of body 1; a revolute cut between body 3 and the
/// ground adds the orientation rows (u·w = 0) and their geometric stiffness.
Model randomSpatialChain(Random& rng) {
  constexpr int kBodies = 6;
  Model model;
  std::vector<FrameIndex> body_frames;
  FrameIndex parent = Model::ground;
  for (int k = 0; k < kBodies; ++k) {
    const std::string id = std::to_string(k);
    parent = model.addOffset("offset" + id, parent, rng.vector(-0.4, 0.4), rng.rotation());
    // Pattern over k: (R,R) (P,R) (R,P) (P,R) (R,R) (P,P) — both kinds at every depth.
    const bool first_revolute = k % 2 == 0;
    const bool second_revolute = k % 3 != 2 && k != 5;
    if (k == 3) parent = model.addBallJoint({"ball_x", "ball_y", "ball_z"}, parent);  // its chart beyond θ = 1
    parent = first_revolute ? model.addRevolute("joint" + id + "a", parent, rng.obliqueAxis())
                            : model.addPrismatic("joint" + id + "a", parent, rng.obliqueAxis());
    parent = second_revolute ? model.addRevolute("joint" + id + "b", parent, rng.obliqueAxis())
                             : model.addPrismatic("joint" + id + "b", parent, rng.obliqueAxis());
    const double mass = rng.uniform(0.5, 3.0);
    model.addBody("body" + id, parent, mass, rng.vector(-0.25, 0.25), rng.inertia(mass));
    body_frames.push_back(parent);
  }
  for (const Coordinate& c : model.coordinates())
    model.addJointSpringDamper(c.name + "_spring", c.name, rng.uniform(5.0, 50.0), rng.uniform(0.5, 5.0),
                               rng.uniform(-0.3, 0.3));
  model.addPointSpringDamper("strut", body_frames[1], rng.vector(-0.2, 0.2), body_frames[4], rng.vector(-0.2, 0.2),
                             rng.uniform(50.0, 200.0), rng.uniform(2.0, 10.0), rng.uniform(0.1, 0.3));
  model.setGravity(9.81 * rng.obliqueAxis());

  const FrameIndex tip = model.addOffset("tip", body_frames[5], rng.vector(-0.3, 0.3), rng.rotation());
  const FrameIndex anchor = model.addOffset("anchor", body_frames[1], rng.vector(-0.3, 0.3), rng.rotation());
  model.addSphericalCut("loop", tip, anchor);
  const FrameIndex hinge = model.addOffset("hinge", body_frames[3], rng.vector(-0.3, 0.3), rng.rotation());
  const FrameIndex bearing = model.addOffset("bearing", Model::ground, rng.vector(-0.5, 0.5), rng.rotation());
  model.addRevoluteCut("hinge_cut", hinge, bearing, rng.obliqueAxis(), rng.obliqueAxis());
  return model;
}

/// A tree with branches and no loop (7 + 2 + 3 coordinates): a trunk body on a revolute and a prismatic
/// joint from the ground carries two chains whose elements are added interleaved (so the topological
/// order is not a depth-first one), a third chain hangs from the massless frame between the trunk's
/// two joints, and a second chain stands on the ground, ending in a ball joint. Some bodies sit on
/// offset frames.
Model randomBranchedTree(Random& rng) {
  Model model;
  const auto body = [&](const std::string& name, FrameIndex frame) {
    const double mass = rng.uniform(0.5, 3.0);
    model.addBody(name + "_body", frame, mass, rng.vector(-0.25, 0.25), rng.inertia(mass));
  };
  const FrameIndex base = model.addOffset("base", Model::ground, rng.vector(-0.4, 0.4), rng.rotation());
  const FrameIndex trunk_hinge = model.addRevolute("trunk_a", base, rng.obliqueAxis());
  const FrameIndex trunk = model.addPrismatic("trunk_b", trunk_hinge, rng.obliqueAxis());
  body("trunk", trunk);
  FrameIndex left = model.addOffset("left_offset", trunk, rng.vector(-0.4, 0.4), rng.rotation());
  FrameIndex right = model.addOffset("right_offset", trunk, rng.vector(-0.4, 0.4), rng.rotation());
  left = model.addRevolute("left_a", left, rng.obliqueAxis());
  right = model.addPrismatic("right_a", right, rng.obliqueAxis());
  body("right_1", right);
  left = model.addPrismatic("left_b", left, rng.obliqueAxis());
  right = model.addRevolute("right_b", right, rng.obliqueAxis());
  body("left", model.addOffset("left_centre", left, rng.vector(-0.4, 0.4), rng.rotation()));
  body("right_2", right);
  const FrameIndex side = model.addRevolute("side", trunk_hinge, rng.obliqueAxis());
  body("side", model.addOffset("side_centre", side, rng.vector(-0.4, 0.4), rng.rotation()));
  const FrameIndex other = model.addRevolute("other_a", Model::ground, rng.obliqueAxis());
  body("other_1", other);
  body("other_2", model.addPrismatic("other_b", other, rng.obliqueAxis()));
  const FrameIndex ball = model.addBallJoint({"ball_x", "ball_y", "ball_z"}, model.frame("other_b"));
  body("other_3", model.addOffset("other_3_centre", ball, rng.vector(-0.4, 0.4), rng.rotation()));
  model.setGravity(9.81 * rng.obliqueAxis());
  // Rotor inertias on a hinge deep in the tree, a slide and a hinge on the ground: J on M's
  // diagonal, which the CRBA, the articulated-body pivots and the AD residual must each carry.
  for (const char* joint : {"left_a", "right_a", "other_a"}) model.addArmature(joint, rng.uniform(0.05, 0.5));
  return model;
}

using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

double maxAbs(const Eigen::MatrixXd& A) { return A.size() ? A.cwiseAbs().maxCoeff() : 0.0; }

struct FiniteDifference {
  Eigen::MatrixXd jacobian;
  double value_scale;  ///< ‖F(x)‖_max: what the round-off of the differences is proportional to
};

/// Central-difference Jacobian: column j = (F(x + h_j e_j) − F(x − h_j e_j)) / (2 h_j),
/// h_j = kRelativeStep · max(1, |x_j|).
FiniteDifference centralDifferenceJacobian(const VectorFunction& F, const Eigen::VectorXd& x) {
  const Eigen::VectorXd value = F(x);
  FiniteDifference fd{Eigen::MatrixXd(value.size(), x.size()), maxAbs(value)};
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double h = kRelativeStep * std::max(1.0, std::abs(x[j]));
    Eigen::VectorXd plus = x, minus = x;
    plus[j] += h;
    minus[j] -= h;
    fd.jacobian.col(j) = (F(plus) - F(minus)) / (2.0 * h);
  }
  return fd;
}

/// ‖actual − reference‖_max ≤ tolerance · max(‖reference‖_max, extra_scale), with the numbers in
/// the failure message.
void expectRelativelyClose(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& reference, double tolerance,
                           const std::string& what, double extra_scale = 0.0) {
  ASSERT_EQ(actual.rows(), reference.rows()) << what;
  ASSERT_EQ(actual.cols(), reference.cols()) << what;
  ASSERT_GT(maxAbs(reference), 0.0) << what << " is identically zero: the check would be vacuous";
  const double scale = std::max(maxAbs(reference), extra_scale);
  const double error = maxAbs(actual - reference);
  EXPECT_LE(error, tolerance * scale) << what << ": max |difference| " << error << ", max |entry| " << scale
                                      << ", relative " << error / scale;
}

void expectMatchesFiniteDifference(const Eigen::MatrixXd& exact, const FiniteDifference& fd, const std::string& what) {
  expectRelativelyClose(exact, fd.jacobian, kFdTolerance, what, fd.value_scale);
}

class TangentMatricesTest : public ::testing::Test {
 protected:
  static constexpr double kTime = 0.3;

  TangentMatricesTest()
      : rng_(20240611u), model_(randomSpatialChain(rng_)), ws_(model_), jacobian_ws_(model_), ad_ws_(model_) {
    const Eigen::Index n = model_.coordinateCount();
    q_ = rng_.vector(n, -1.0, 1.0);
    v_ = rng_.vector(n, -2.0, 2.0);
    a_ = rng_.vector(n, -5.0, 5.0);
    lambda_ = rng_.vector(model_.constraintCount(), -20.0, 20.0);
  }

  Eigen::VectorXd residualAt(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
    Eigen::VectorXd f;
    residual(model_, ws_, q, v, a, lambda_, kTime, f);
    return f;
  }

  Eigen::VectorXd closureAt(const Eigen::VectorXd& q, Derivative level) {
    const KinematicsLevel kinematics = level == Derivative::Position   ? KinematicsLevel::Position
                                       : level == Derivative::Velocity ? KinematicsLevel::Velocity
                                                                       : KinematicsLevel::Acceleration;
    forwardKinematics(model_, ws_, q, v_, a_, kinematics);
    Eigen::VectorXd b;
    closureEquations(model_, ws_, level, b);
    return b;
  }

  Eigen::MatrixXd jacobianAt(const Eigen::VectorXd& q) {
    Eigen::VectorXd b;
    Eigen::MatrixXd B;
    constraintJacobian(model_, jacobian_ws_, q, b, B);
    return B;
  }

  /// ∂(the closure rows at `level`)/∂q, or ∂/∂q̇ with `velocities`, at (q_, v_, a_): forward AD in
  /// passes of kMaxAdDirections, independently of the gradients' passes.
  Eigen::MatrixXd closureDerivative(Derivative level, bool velocities) {
    const Eigen::Index n = model_.coordinateCount(), m = model_.constraintCount();
    Eigen::MatrixXd out(m, n);
    VectorX<AdScalar> q, v, a, b;
    for (Eigen::Index first = 0; first < n; first += kMaxAdDirections) {
      const Eigen::Index count = std::min<Eigen::Index>(kMaxAdDirections, n - first);
      seedVector(q_, 0, first, velocities ? 0 : count, q);
      seedVector(v_, 0, first, velocities ? count : 0, v);
      seedVector(a_, 0, 0, 0, a);
      forwardKinematics(model_, ad_ws_, q, v, a, KinematicsLevel::Acceleration);
      closureEquations(model_, ad_ws_, level, b);
      for (Eigen::Index i = 0; i < m; ++i) out.row(i).segment(first, count) = b[i].derivatives().head(count);
    }
    return out;
  }

  TangentMatrices exactTangents() {
    TangentMatrices t;
    tangentMatrices(model_, ad_ws_, q_, v_, a_, lambda_, kTime, t);
    return t;
  }

  Random rng_;
  Model model_;
  Workspace<double> ws_, jacobian_ws_;
  Workspace<AdScalar> ad_ws_;
  Eigen::VectorXd q_, v_, a_, lambda_;
};

TEST_F(TangentMatricesTest, ModelHasTheIntendedSize) {
  EXPECT_EQ(model_.coordinateCount(), 15);
  EXPECT_EQ(model_.bodies().size(), 6u);
  EXPECT_EQ(model_.constraintCount(), 3 + 5);
  EXPECT_GT(3 * model_.coordinateCount(), kMaxAdDirections);  // exercises the multi-pass seeding
}

TEST_F(TangentMatricesTest, ResidualOfTheAdPassEqualsTheDoubleResidual) {
  expectRelativelyClose(exactTangents().residual, residualAt(q_, v_, a_), kIdentityTolerance, "f (AD vs double)");
}

TEST_F(TangentMatricesTest, MassMatrixMatchesFiniteDifferencesAndIsSymmetricPositiveDefinite) {
  const Eigen::MatrixXd M = exactTangents().mass;
  const FiniteDifference fd = centralDifferenceJacobian([&](const Eigen::VectorXd& a) { return residualAt(q_, v_, a); }, a_);
  expectMatchesFiniteDifference(M, fd, "M = ∂f/∂q̈");
  // M = Σ Jᵀ M_body J: symmetric to round-off, positive definite since every joint moves a body.
  expectRelativelyClose(M.transpose(), M, kIdentityTolerance, "Mᵀ vs M");
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
  EXPECT_GT(eigenvalues.minCoeff(), 0.0);
}

TEST_F(TangentMatricesTest, DampingMatrixMatchesFiniteDifferences) {
  const FiniteDifference fd = centralDifferenceJacobian([&](const Eigen::VectorXd& v) { return residualAt(q_, v, a_); }, v_);
  expectMatchesFiniteDifference(exactTangents().damping, fd, "C_T = ∂f/∂q̇");
}

TEST_F(TangentMatricesTest, StiffnessMatrixMatchesFiniteDifferences) {
  const FiniteDifference fd = centralDifferenceJacobian([&](const Eigen::VectorXd& q) { return residualAt(q, v_, a_); }, q_);
  expectMatchesFiniteDifference(exactTangents().stiffness, fd, "K_T = ∂f/∂q");
}

TEST_F(TangentMatricesTest, StiffnessIncludesTheGeometricStiffnessOfTheLoopForces) {
  // K_T(λ) − K_T(0) = ∂(Bᵀλ)/∂q must be non-zero and match the FD of Bᵀλ alone, which is what
  // distinguishes a correct tangent from one that treats the loop forces as constant.
  const TangentMatrices with_loads = exactTangents();
  const Eigen::VectorXd saved = lambda_;
  lambda_.setZero();
  const TangentMatrices without_loads = exactTangents();
  lambda_ = saved;
  const Eigen::MatrixXd geometric = with_loads.stiffness - without_loads.stiffness;
  const FiniteDifference fd = centralDifferenceJacobian(
      [&](const Eigen::VectorXd& q) { return Eigen::VectorXd(jacobianAt(q).transpose() * lambda_); }, q_);
  expectMatchesFiniteDifference(geometric, fd, "∂(Bᵀλ)/∂q");
}

TEST_F(TangentMatricesTest, ConstraintJacobianMatchesFiniteDifferencesOfTheClosure) {
  const FiniteDifference fd =
      centralDifferenceJacobian([&](const Eigen::VectorXd& q) { return closureAt(q, Derivative::Position); }, q_);
  expectMatchesFiniteDifference(jacobianAt(q_), fd, "B = ∂b/∂q");
}

// What the topology fixes, set as elements are added: each element's nearest joint towards the ground
// (the mass matrix walks these) and each frame's depth (elements from the ground, in the round-off
// scale of an orthogonality closure row), read off by hand for two branches with offsets between
// the joints.
TEST(ModelTopology, ParentJointsAndDepthsFollowThePathsToTheGround) {
  Model model;
  const FrameIndex o1 = model.addOffset("o1", Model::ground, {1, 0, 0});  // element 0, passive
  const FrameIndex r1 = model.addRevolute("r1", o1, {0, 0, 1});            // 1, active
  const FrameIndex o2 = model.addOffset("o2", r1, {1, 0, 0});              // 2, passive
  const FrameIndex p1 = model.addPrismatic("p1", o2, {1, 0, 0});           // 3, active
  const FrameIndex o3 = model.addOffset("o3", p1, {0, 1, 0});              // 4, passive
  const FrameIndex r2 = model.addRevolute("r2", o3, {0, 0, 1});            // 5, active
  const FrameIndex r3 = model.addRevolute("r3", Model::ground, {0, 0, 1}); // 6, active
  const FrameIndex o4 = model.addOffset("o4", r3, {1, 0, 0});              // 7, passive
  std::vector<int> parent_joints;
  for (const KinematicElement& element : model.elements()) parent_joints.push_back(element.parent_joint);
  EXPECT_EQ(parent_joints, (std::vector<int>{-1, -1, 1, 1, 3, 3, -1, 6}));
  std::vector<int> depths;
  for (const FrameIndex f : {Model::ground, o1, r1, o2, p1, o3, r2, r3, o4})
    depths.push_back(model.frames()[static_cast<std::size_t>(f)].depth);
  EXPECT_EQ(depths, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 1, 2}));
}

// A model may get joints after a cut joint (the cut frames' paths from the ground are recorded with
// the cut, Model::cutFramePaths): B's columns of the later joints, one on the path of neither cut
// frame and one beyond a cut frame's branch, must still be the closure's derivatives.
TEST(ConstraintJacobian, JointsAddedAfterACutHaveTheirColumns) {
  Random rng(20261125u);
  Model model;
  FrameIndex a = Model::ground, b = Model::ground;
  for (int k = 0; k < 3; ++k) {
    a = model.addRevolute("left" + std::to_string(k), model.addOffset("left_arm" + std::to_string(k), a, rng.vector(-0.4, 0.4), rng.rotation()), rng.obliqueAxis());
    b = model.addRevolute("right" + std::to_string(k), model.addOffset("right_arm" + std::to_string(k), b, rng.vector(-0.4, 0.4), rng.rotation()), rng.obliqueAxis());
  }
  model.addSphericalCut("loop", a, b);
  const FrameIndex side = model.addRevolute("side", Model::ground, rng.obliqueAxis());  // moves no cut frame
  model.addBody("side_body", side, 1.0, rng.vector(-0.2, 0.2), rng.inertia(1.0));
  const FrameIndex beyond = model.addPrismatic("beyond", b, rng.obliqueAxis());  // after b: moves no cut frame either
  model.addBody("beyond_body", beyond, 1.0, rng.vector(-0.2, 0.2), rng.inertia(1.0));
  for (const Model::CutFramePath& path : model.cutFramePaths())
    EXPECT_EQ(path.on_path.size(), model.elements().size());
  Workspace<double> ws(model);
  const Eigen::VectorXd q = rng.vector(model.coordinateCount(), -1.0, 1.0);
  Eigen::VectorXd b0;
  Eigen::MatrixXd B;
  constraintJacobian(model, ws, q, b0, B);
  const FiniteDifference fd = centralDifferenceJacobian(
      [&](const Eigen::VectorXd& x) {
        forwardKinematics(model, ws, x, x, x, KinematicsLevel::Position);
        Eigen::VectorXd closure;
        closureEquations(model, ws, Derivative::Position, closure);
        return closure;
      },
      q);
  expectMatchesFiniteDifference(B, fd, "B with joints added after the cut");
  EXPECT_EQ(B.col(model.coordinate("side")).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(B.col(model.coordinate("beyond")).cwiseAbs().maxCoeff(), 0.0);
}

TEST_F(TangentMatricesTest, VelocityClosureIsJacobianTimesVelocity) {
  // No driven coordinate, so ∂b/∂t = 0 and ḃ = B q̇ exactly.
  const Eigen::VectorXd expected = jacobianAt(q_) * v_;
  expectRelativelyClose(closureAt(q_, Derivative::Velocity), expected, kIdentityTolerance, "ḃ vs B q̇");
}

TEST_F(TangentMatricesTest, AccelerationClosureIsJacobianTimesAccelerationPlusItsRateTimesVelocity) {
  // b̈ = B q̈ + Ḃ q̇ along q(t) = q + q̇t + q̈t²/2; Ḃ by a central difference in t (error O(τ²)·‖B⃛‖
  // plus ε‖B‖/τ: both ≈ 1e-10 relative for τ = 1e-6).
  constexpr double tau = 1e-6;
  const auto path = [&](double t) { return Eigen::VectorXd(q_ + v_ * t + 0.5 * a_ * t * t); };
  const Eigen::MatrixXd B_rate = (jacobianAt(path(tau)) - jacobianAt(path(-tau))) / (2.0 * tau);
  const Eigen::VectorXd expected = jacobianAt(q_) * a_ + B_rate * v_;
  expectRelativelyClose(closureAt(q_, Derivative::Acceleration), expected, kFdTolerance, "b̈ vs B q̈ + Ḃ q̇");
}

TEST_F(TangentMatricesTest, AccelerationClosureRateDerivativeIsTwiceTheVelocityClosurePositionDerivative) {
  // b depends on q alone: ḃ = B q̇, b̈ = B q̈ + Ḃ q̇, so ∂b̈/∂q̇_j = Ḃ e_j + (∂B/∂q_j) q̇, and both terms are
  // ∂ḃ/∂q_j because b's second derivatives are symmetric. The gradients use ∂b̈/∂q̇ = 2 ∂ḃ/∂q
  // (ClosureDerivatives); here both sides by AD, through different rows of the closure.
  const Eigen::MatrixXd rate_derivative = closureDerivative(Derivative::Acceleration, /*velocities=*/true);
  const Eigen::MatrixXd twice_position_derivative = 2.0 * closureDerivative(Derivative::Velocity, false);
  expectRelativelyClose(rate_derivative, twice_position_derivative, kIdentityTolerance, "∂b̈/∂q̇ vs 2 ∂ḃ/∂q");
}

TEST_F(TangentMatricesTest, CompositeRigidBodyMassMatrixEqualsTheAdMass) {
  // The CRBA mass matrix, all coordinates and a block on an unordered subset, against the AD mass,
  // on the fixture's chain and on a branched tree.
  const auto expectEqualsAdMass = [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                     const std::vector<int>& subset, const std::string& what) {
    Workspace<AdScalar> ad_ws(model);
    TangentMatrices tangents;
    tangentMatrices(model, ad_ws, q, v, a, lambda, kTime, tangents);
    Workspace<double> ws(model);
    forwardKinematics(model, ws, q, v, a, KinematicsLevel::Velocity);
    Eigen::MatrixXd M, block;
    massMatrix(model, ws, M);
    massMatrix(model, ws, subset, block);
    expectRelativelyClose(M, tangents.mass, kIdentityTolerance, what + ": CRBA M vs AD M");
    expectRelativelyClose(block, tangents.mass(subset, subset), kIdentityTolerance, what + ": CRBA block vs AD block",
                          maxAbs(tangents.mass));
  };
  expectEqualsAdMass(model_, q_, v_, a_, lambda_, {7, 2, 11, 4, 0, 9}, "spatial chain");

  Random rng(20240612u);
  const Model tree = randomBranchedTree(rng);
  ASSERT_EQ(tree.coordinateCount(), 12);
  const Eigen::Index n = tree.coordinateCount();
  const Eigen::VectorXd q = rng.vector(n, -1.0, 1.0), v = rng.vector(n, -2.0, 2.0), a = rng.vector(n, -5.0, 5.0);
  const std::vector<int> subset = {tree.coordinate("right_b"), tree.coordinate("left_a"), tree.coordinate("side"),
                                   tree.coordinate("other_b"), tree.coordinate("trunk_a")};
  expectEqualsAdMass(tree, q, v, a, Eigen::VectorXd(), subset, "branched tree");
}

TEST_F(TangentMatricesTest, ArticulatedBodySolveInvertsTheAdMass) {
  // x = M⁻¹τ by the articulated-body recursion, on all coordinates and on unordered subsets (the
  // others locked), against the AD mass block: the residual M x − τ is a backward error, a few ε
  // times ‖M‖‖x‖ for a stable factorization whatever M's condition, while a wrong shift, a missing
  // body or a misplaced node leaves a residual of the order of τ itself.
  const auto expectInverts = [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, const std::vector<int>& subset,
                                Random& rng, const std::string& what) {
    Workspace<AdScalar> ad_ws(model);
    TangentMatrices tangents;
    tangentMatrices(model, ad_ws, q, v, a, lambda, kTime, tangents);
    const Eigen::MatrixXd M = tangents.mass(subset, subset);
    Workspace<double> ws(model);
    forwardKinematics(model, ws, q, v, a, KinematicsLevel::Velocity);
    ArticulatedBodyFactorization factorization;
    ASSERT_TRUE(factorization.factor(model, ws, subset)) << what;
    ASSERT_EQ(factorization.size(), static_cast<Eigen::Index>(subset.size())) << what;
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd tau = rng.vector(static_cast<Eigen::Index>(subset.size()), -10.0, 10.0);
      Eigen::VectorXd x;
      factorization.solve(tau, x);
      const double residual = maxAbs(M * x - tau);
      EXPECT_LE(residual, kIdentityTolerance * maxAbs(M) * maxAbs(x))
          << what << ": max |M x − τ| " << residual << " for max |τ| " << maxAbs(tau);
    }
  };
  std::vector<int> all(static_cast<std::size_t>(model_.coordinateCount()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  expectInverts(model_, q_, v_, a_, lambda_, all, rng_, "spatial chain, all coordinates");
  expectInverts(model_, q_, v_, a_, lambda_, {7, 2, 11, 4, 0, 9}, rng_, "spatial chain, a subset");

  Random rng(20240613u);
  const Model tree = randomBranchedTree(rng);
  const Eigen::Index n = tree.coordinateCount();
  const Eigen::VectorXd q = rng.vector(n, -1.0, 1.0), v = rng.vector(n, -2.0, 2.0), a = rng.vector(n, -5.0, 5.0);
  expectInverts(tree, q, v, a, Eigen::VectorXd(), {8, 3, 0, 5, 1, 7, 2, 6, 4}, rng, "branched tree, all, shuffled");
  const std::vector<int> subset = {tree.coordinate("right_b"), tree.coordinate("left_a"), tree.coordinate("side"),
                                   tree.coordinate("other_b"), tree.coordinate("trunk_a")};
  expectInverts(tree, q, v, a, Eigen::VectorXd(), subset, rng, "branched tree, a subset");
}

}  // namespace
}  // namespace mbsopt
