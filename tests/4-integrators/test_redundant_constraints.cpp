// Redundant loop-closure equations handled by the SVD partition of the Newmark integrator:
//  (a) a planar four-bar closed by a spatial revolute cut (5 equations, rank 2) or a spherical cut
//      (3 equations, rank 2) against the same four-bar made non-redundant (3 equations, rank 3) and
//      against the one-degree-of-freedom equation of motion derived by hand (Lagrange, loop solved
//      in closed form) and integrated by RK4;
//  (b) a parallelogram linkage with a redundant third crank against the plain parallelogram
//      carrying the same masses, its closed-form kinematics (the coupler translates) and its exact
//      pendulum equation.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/assembly.hpp"
#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/algorithms/tangent.hpp"
#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;
constexpr double kGravity = 9.81;
constexpr double kLinearDensity = 2.0;  // [kg/m]
constexpr double kBarWidth = 0.03;      // square cross-section [m]
constexpr double kStep = 1e-3;
constexpr double kEndTime = 3.0;
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();
const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();

// Uniform slender bar along x from its frame's origin.
double barMass(double length) { return kLinearDensity * length; }
double barInertiaZ(double length) { return barMass(length) * (length * length + kBarWidth * kBarWidth) / 12.0; }
void addBar(Model& model, const std::string& name, FrameIndex frame, double length) {
  const double axial = barMass(length) * kBarWidth * kBarWidth / 6.0;
  model.addBody(name, frame, barMass(length), 0.5 * length * kX,
                Eigen::Vector3d(axial, barInertiaZ(length), barInertiaZ(length)).asDiagonal());
}

Eigen::Vector2d along(double angle) { return {std::cos(angle), std::sin(angle)}; }
Eigen::Vector2d across(double angle) { return {-std::sin(angle), std::cos(angle)}; }  // d along/d angle

Trajectory simulate(const Model& model, const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, double step) {
  NewmarkSettings settings;
  settings.step = step;
  settings.end_time = kEndTime;
  return NewmarkIntegrator(model, settings).simulate(q0, v0);
}

/// θ(t) at t = k·output_step, k = 0 … count−1, of θ̈ = acceleration(θ, θ̇) by classical RK4 with ten
/// substeps per output step: global error O((ωh/10)⁴) ≈ 1e-13, negligible against Newmark's O(h²).
using ScalarOde = std::function<double(double, double)>;
Eigen::VectorXd integrateRk4(const ScalarOde& acceleration, double theta, double rate, double output_step,
                             Eigen::Index count) {
  constexpr int kSubsteps = 10;
  const double h = output_step / kSubsteps;
  Eigen::VectorXd history(count);
  for (Eigen::Index k = 0; k < count; ++k) {
    history[k] = theta;
    for (int s = 0; s < kSubsteps; ++s) {
      const double k1x = rate, k1v = acceleration(theta, rate);
      const double k2x = rate + 0.5 * h * k1v, k2v = acceleration(theta + 0.5 * h * k1x, k2x);
      const double k3x = rate + 0.5 * h * k2v, k3v = acceleration(theta + 0.5 * h * k2x, k3x);
      const double k4x = rate + h * k3v, k4v = acceleration(theta + h * k3x, k4x);
      theta += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
      rate += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
  }
  return history;
}

double maxDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).cwiseAbs().maxCoeff(); }

/// Rank of B over the free coordinates at q, as the integrator's partition sees it.
SvdPartition partitionAt(const Model& model, const Eigen::VectorXd& q) {
  Workspace<double> ws(model);
  Eigen::VectorXd b;
  Eigen::MatrixXd B;
  constraintJacobian(model, ws, q, b, B);
  Eigen::MatrixXd B_free(B.rows(), static_cast<Eigen::Index>(model.freeCoordinates().size()));
  for (std::size_t k = 0; k < model.freeCoordinates().size(); ++k)
    B_free.col(static_cast<Eigen::Index>(k)) = B.col(model.freeCoordinates()[k]);
  SvdPartition partition(NewmarkSettings{}.svd_threshold);
  partition.setConstraintJacobian(B_free);
  return partition;
}

/// The rank decision must not hinge on the threshold: singular values dropped as redundant are
/// round-off (≤ 1e-12 of the largest), those kept are of order one (≥ 1e-2 of the largest).
void expectRank(const SvdPartition& partition, int rank, int rows) {
  EXPECT_EQ(partition.constraintRows(), rows);
  ASSERT_EQ(partition.rank(), rank);
  const Eigen::VectorXd& s = partition.singularValues();
  EXPECT_GE(s[rank - 1], 1e-2 * s[0]);
  if (s.size() > rank) {
    EXPECT_LE(s.tail(s.size() - rank).maxCoeff(), 1e-12 * s[0]);
  }
}

// ======================================= (a) four-bar =======================================
// Grashof crank-rocker (0.3 + 1.0 ≤ 0.8 + 1.0, crank shortest): no dead point, the loop Jacobian
// keeps rank 2 while the crank turns.
constexpr double kGround = 1.0, kCrank = 0.3, kCoupler = 1.0, kRocker = 0.8;

enum class FourBarClosure {
  RevoluteCut,            ///< 5 equations: p_a = p_b (x, y, z) and z_a ⟂ two directions of b; rank 2
  SphericalCut,           ///< 3 equations: x, y, z; the z row is identically zero; rank 2
  SphericalCutOnZSlider,  ///< 3 equations, rank 3: the rocker tip rides a massless slider along z,
                          ///< which makes the z row a genuine equation (it holds the slider at 0)
};

/// Coordinates: crank angle, coupler angle relative to the crank, rocker angle [, slider along z].
Model fourBar(FourBarClosure closure) {
  Model model;
  const FrameIndex crank = model.addRevolute("crank", Model::ground, kZ);
  addBar(model, "crank_bar", crank, kCrank);
  const FrameIndex coupler = model.addRevolute("coupler", model.addOffset("crank_tip", crank, kCrank * kX), kZ);
  addBar(model, "coupler_bar", coupler, kCoupler);
  const FrameIndex coupler_tip = model.addOffset("coupler_tip", coupler, kCoupler * kX);
  const FrameIndex rocker = model.addRevolute("rocker", model.addOffset("rocker_pivot", Model::ground, kGround * kX), kZ);
  addBar(model, "rocker_bar", rocker, kRocker);
  FrameIndex rocker_tip = model.addOffset("rocker_tip", rocker, kRocker * kX);
  switch (closure) {
    case FourBarClosure::RevoluteCut: model.addRevoluteCut("loop", coupler_tip, rocker_tip, kZ, kZ); break;
    case FourBarClosure::SphericalCut: model.addSphericalCut("loop", coupler_tip, rocker_tip); break;
    case FourBarClosure::SphericalCutOnZSlider:
      rocker_tip = model.addPrismatic("rocker_tip_slider", rocker_tip, kZ);
      model.addSphericalCut("loop", coupler_tip, rocker_tip);
      break;
  }
  model.setGravity(Eigen::Vector3d(0.0, -kGravity, 0.0));
  return model;
}

/// Closed-form loop of the four-bar for a crank angle θ: absolute coupler and rocker angles φ, ψ
/// (elbow-up branch, the rocker tip above the ground line) and their first and second derivatives
/// with respect to θ, from the loop a e(θ) + b e(φ) − c e(ψ) − d e_x = 0 differentiated twice:
///   b φ' n(φ) − c ψ' n(ψ) = −a n(θ)
///   b φ'' n(φ) − c ψ'' n(ψ) = a e(θ) + b φ'² e(φ) − c ψ'² e(ψ),     e = (cos, sin), n = e'.
struct FourBarLoop {
  double coupler, rocker;
  double coupler_ratio, rocker_ratio;  // φ', ψ'
  double coupler_ratio_rate, rocker_ratio_rate;  // φ'', ψ''
};

FourBarLoop solveLoop(double theta) {
  FourBarLoop loop{};
  const Eigen::Vector2d crank_tip = kCrank * along(theta);
  const Eigen::Vector2d rocker_pivot(kGround, 0.0);
  const Eigen::Vector2d diagonal = crank_tip - rocker_pivot;
  const double e = diagonal.norm();
  const double at_pivot = std::acos((kRocker * kRocker + e * e - kCoupler * kCoupler) / (2.0 * kRocker * e));
  loop.rocker = std::atan2(diagonal.y(), diagonal.x()) - at_pivot;
  const Eigen::Vector2d link = rocker_pivot + kRocker * along(loop.rocker) - crank_tip;
  loop.coupler = std::atan2(link.y(), link.x());
  Eigen::Matrix2d A;
  A << kCoupler * across(loop.coupler), -kRocker * across(loop.rocker);
  const Eigen::PartialPivLU<Eigen::Matrix2d> lu(A);
  const Eigen::Vector2d ratios = lu.solve(-kCrank * across(theta));
  loop.coupler_ratio = ratios[0];
  loop.rocker_ratio = ratios[1];
  const Eigen::Vector2d rates = lu.solve(kCrank * along(theta) + kCoupler * ratios[0] * ratios[0] * along(loop.coupler) -
                                         kRocker * ratios[1] * ratios[1] * along(loop.rocker));
  loop.coupler_ratio_rate = rates[0];
  loop.rocker_ratio_rate = rates[1];
  return loop;
}

/// Lagrange's equation in the crank angle: T = ½ m(θ) θ̇², V(θ) = −Σ m_k g·r_k(θ), so
///   θ̈ = (Σ m_k g·J_k − θ̇² Σ (m_k J_k·J_k' + I_k w_k w_k')) / m(θ),  m = Σ m_k J_k·J_k + I_k w_k²,
/// with J_k = ∂r_k/∂θ (centre of mass), w_k = ∂ω_k/∂θ, and their θ-derivatives for each bar.
double fourBarCrankAcceleration(double theta, double rate) {
  const FourBarLoop s = solveLoop(theta);
  struct BarMotion {
    double length;
    Eigen::Vector2d J, dJ;
    double w, dw;
  };
  const BarMotion bars[] = {
      {kCrank, 0.5 * kCrank * across(theta), -0.5 * kCrank * along(theta), 1.0, 0.0},
      {kCoupler, kCrank * across(theta) + 0.5 * kCoupler * s.coupler_ratio * across(s.coupler),
       -kCrank * along(theta) + 0.5 * kCoupler *
                                    (s.coupler_ratio_rate * across(s.coupler) -
                                     s.coupler_ratio * s.coupler_ratio * along(s.coupler)),
       s.coupler_ratio, s.coupler_ratio_rate},
      {kRocker, 0.5 * kRocker * s.rocker_ratio * across(s.rocker),
       0.5 * kRocker * (s.rocker_ratio_rate * across(s.rocker) - s.rocker_ratio * s.rocker_ratio * along(s.rocker)),
       s.rocker_ratio, s.rocker_ratio_rate}};
  const Eigen::Vector2d g(0.0, -kGravity);
  double mass = 0.0, gravity = 0.0, centripetal = 0.0;
  for (const BarMotion& bar : bars) {
    const double m = barMass(bar.length), I = barInertiaZ(bar.length);
    mass += m * bar.J.squaredNorm() + I * bar.w * bar.w;
    gravity += m * g.dot(bar.J);
    centripetal += m * bar.J.dot(bar.dJ) + I * bar.w * bar.dw;
  }
  return (gravity - rate * rate * centripetal) / mass;
}

constexpr double kFourBarCrank0 = 60.0 * kDegree;
constexpr double kFourBarRate0 = 3.0;  // [rad/s]: the crank turns over (about 2 revolutions in 3 s)

/// Exact state on the loop for the crank at (kFourBarCrank0, kFourBarRate0); the slider, if any, at 0.
void fourBarState(const Model& model, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  const FourBarLoop s = solveLoop(kFourBarCrank0);
  q = Eigen::VectorXd::Zero(model.coordinateCount());
  v = Eigen::VectorXd::Zero(model.coordinateCount());
  q.head<3>() << kFourBarCrank0, s.coupler - kFourBarCrank0, s.rocker;
  v.head<3>() << 1.0, s.coupler_ratio - 1.0, s.rocker_ratio;
  v *= kFourBarRate0;
}

struct FourBarRun {
  Model model;
  Eigen::VectorXd q0, v0;
  Trajectory coarse, fine;  ///< h and h/2
};

FourBarRun runFourBar(FourBarClosure closure, bool with_fine) {
  FourBarRun run{fourBar(closure), {}, {}, {}, {}};
  fourBarState(run.model, run.q0, run.v0);
  assemble(run.model, run.q0, run.v0, 0.0);  // already closed: polishes round-off only
  run.coarse = simulate(run.model, run.q0, run.v0, kStep);
  if (with_fine) run.fine = simulate(run.model, run.q0, run.v0, 0.5 * kStep);
  return run;
}

class RedundantFourBarTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    revolute_ = std::make_unique<FourBarRun>(runFourBar(FourBarClosure::RevoluteCut, true));
    spherical_ = std::make_unique<FourBarRun>(runFourBar(FourBarClosure::SphericalCut, false));
    non_redundant_ = std::make_unique<FourBarRun>(runFourBar(FourBarClosure::SphericalCutOnZSlider, false));
  }
  static void TearDownTestSuite() {
    revolute_.reset();
    spherical_.reset();
    non_redundant_.reset();
  }
  static Eigen::VectorXd crank(const Trajectory& t) { return t.q.row(0).transpose(); }
  static Eigen::VectorXd reference(double step, Eigen::Index count) {
    return integrateRk4(fourBarCrankAcceleration, revolute_->q0[0], revolute_->v0[0], step, count);
  }

  static inline std::unique_ptr<FourBarRun> revolute_, spherical_, non_redundant_;
};

TEST_F(RedundantFourBarTest, PartitionFindsTheRankOfEachClosure) {
  expectRank(partitionAt(revolute_->model, revolute_->q0), 2, 5);
  expectRank(partitionAt(spherical_->model, spherical_->q0), 2, 3);
  expectRank(partitionAt(non_redundant_->model, non_redundant_->q0), 3, 3);
}

TEST_F(RedundantFourBarTest, AllClosuresStayClosed) {
  for (const FourBarRun* run : {revolute_.get(), spherical_.get(), non_redundant_.get()})
    EXPECT_LE(run->coarse.statistics.max_closure_error, 1e-9);
  // The slider of the non-redundant model is held at z = 0 by the genuine z equation.
  EXPECT_LE(non_redundant_->coarse.q.row(3).cwiseAbs().maxCoeff(), 1e-9);
}

TEST_F(RedundantFourBarTest, RedundantClosuresGiveTheMotionOfTheNonRedundantOne) {
  // All three discretise the same one-degree-of-freedom motion with the same step: their Newmark
  // solutions coincide up to the Newton tolerance (1e-10 relative on q̈ each step) accumulated
  // over 3000 steps, far below 1e-8 rad; a mishandled redundancy (wrong multipliers feeding
  // back into the motion, a dropped independent equation) would show at the 1e-3 level or fail.
  const Eigen::VectorXd reference = crank(non_redundant_->coarse);
  EXPECT_LE(maxDifference(crank(revolute_->coarse), reference), 1e-8);
  EXPECT_LE(maxDifference(crank(spherical_->coarse), reference), 1e-8);
}

TEST_F(RedundantFourBarTest, CrankMatchesTheHandDerivedEquationToSecondOrder) {
  // Trapezoidal rule: phase error ≈ (ωh)²/12 per radian travelled. Rates reach ≈ 17 rad/s and the
  // crank travels ≈ 14 rad in 3 s: (0.017)²/12 · 14 ≈ 3.4e-4 rad at h = 1 ms; we allow 2e-3 rad, and
  // halving h must divide the error by ≈ 4 (accepted: ≥ 3), which only a second-order solution does.
  const Eigen::VectorXd coarse = crank(revolute_->coarse);
  const Eigen::VectorXd fine = crank(revolute_->fine);
  const double coarse_error = maxDifference(coarse, reference(kStep, coarse.size()));
  const double fine_error = maxDifference(fine, reference(0.5 * kStep, fine.size()));
  EXPECT_GT(coarse.maxCoeff() - coarse.minCoeff(), 2.0 * kPi) << "the crank should turn over";
  EXPECT_LE(coarse_error, 2e-3);
  EXPECT_GE(coarse_error / fine_error, 3.0) << "h: " << coarse_error << " rad, h/2: " << fine_error << " rad";
}

// ===================================== (b) parallelogram =====================================
// Three equal cranks of length r pivoted on the ground at x = 0, p, 2p, their tips joined by a
// coupler of length 2p. Any two cranks with the coupler form a parallelogram: the coupler
// translates on a circle of radius r and every crank has the same angle θ; the third crank then
// follows without any effect on the kinematics: its two closure equations add only one
// independent row (planar count: 4 coordinates − 3 = 1 DOF, although Grübler predicts 0).
constexpr double kPitch = 0.6, kParallelCrank = 0.4;
constexpr double kParallelCrank0 = -40.0 * kDegree;  // released from rest 50° from hanging straight down

enum class Parallelogram { Plain, RedundantCrank };

/// Coordinates: crank 1 angle, coupler angle relative to crank 1, crank 2 angle [, crank 3 angle].
///
/// The truly equivalent plain model: in the redundant linkage crank 3 turns about its own pivot by
/// exactly the angle θ of crank 1. Its points therefore move as the points of crank 1 shifted by
/// the constant vector 2p e_x: identical velocities, accelerations and angular velocity, and (with
/// gravity along −y) identical potential energy. The plain parallelogram that carries the bar of
/// crank 3 on the frame of crank 1 (same local centre of mass and inertia) thus has the same
/// kinetic and potential energy as functions of (θ, θ̇) and the same motion; only the constraint
/// forces differ (statically indeterminate in the redundant linkage, where the partition returns
/// the minimum-norm multipliers).
Model parallelogram(Parallelogram kind) {
  Model model;
  const FrameIndex crank1 = model.addRevolute("crank1", Model::ground, kZ);
  addBar(model, "crank1_bar", crank1, kParallelCrank);
  const FrameIndex coupler = model.addRevolute("coupler", model.addOffset("crank1_tip", crank1, kParallelCrank * kX), kZ);
  addBar(model, "coupler_bar", coupler, 2.0 * kPitch);
  auto closeWithCrank = [&](int k) {
    const std::string id = std::to_string(k);
    const FrameIndex pivot = model.addOffset("crank" + id + "_pivot", Model::ground, (k - 1) * kPitch * kX);
    const FrameIndex crank = model.addRevolute("crank" + id, pivot, kZ);
    addBar(model, "crank" + id + "_bar", crank, kParallelCrank);
    const FrameIndex tip = model.addOffset("crank" + id + "_tip", crank, kParallelCrank * kX);
    const FrameIndex on_coupler = model.addOffset("coupler_point" + id, coupler, (k - 1) * kPitch * kX);
    model.addSphericalCut("loop" + id, on_coupler, tip);
  };
  closeWithCrank(2);
  if (kind == Parallelogram::RedundantCrank) closeWithCrank(3);
  else addBar(model, "crank3_bar", crank1, kParallelCrank);
  model.setGravity(Eigen::Vector3d(0.0, -kGravity, 0.0));
  return model;
}

/// The coupler translates on a circle of radius r, so the linkage is a compound pendulum:
///   J θ̈ = −g cos θ · (Σ_cranks m r/2 + m_coupler r),  J = Σ_cranks (I_z + m r²/4) + m_coupler r².
double parallelogramCrankAcceleration(double theta, double /*rate*/) {
  const double m_crank = barMass(kParallelCrank), m_coupler = barMass(2.0 * kPitch);
  const double inertia = 3.0 * (barInertiaZ(kParallelCrank) + 0.25 * m_crank * kParallelCrank * kParallelCrank) +
                         m_coupler * kParallelCrank * kParallelCrank;
  const double moment = 3.0 * m_crank * 0.5 * kParallelCrank + m_coupler * kParallelCrank;
  return -kGravity * std::cos(theta) * moment / inertia;
}

struct ParallelogramRun {
  Model model;
  Eigen::VectorXd q0, v0;
  Trajectory coarse, fine;
};

ParallelogramRun runParallelogram(Parallelogram kind, bool with_fine) {
  ParallelogramRun run{parallelogram(kind), {}, {}, {}, {}};
  const Eigen::Index n = run.model.coordinateCount();
  run.q0 = Eigen::VectorXd::Constant(n, kParallelCrank0);  // every crank at θ₀ …
  run.q0[1] = -kParallelCrank0;                            // … and the coupler level
  run.v0 = Eigen::VectorXd::Zero(n);
  assemble(run.model, run.q0, run.v0, 0.0);
  run.coarse = simulate(run.model, run.q0, run.v0, kStep);
  if (with_fine) run.fine = simulate(run.model, run.q0, run.v0, 0.5 * kStep);
  return run;
}

class RedundantParallelogramTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    redundant_ = std::make_unique<ParallelogramRun>(runParallelogram(Parallelogram::RedundantCrank, true));
    plain_ = std::make_unique<ParallelogramRun>(runParallelogram(Parallelogram::Plain, false));
  }
  static void TearDownTestSuite() {
    redundant_.reset();
    plain_.reset();
  }
  static Eigen::VectorXd coordinate(const Trajectory& t, Eigen::Index i) { return t.q.row(i).transpose(); }

  static inline std::unique_ptr<ParallelogramRun> redundant_, plain_;
};

TEST_F(RedundantParallelogramTest, PartitionFindsOneDegreeOfFreedom) {
  // Redundant: 6 equations (two spherical cuts, z rows identically zero), 4 coordinates, rank 3.
  expectRank(partitionAt(redundant_->model, redundant_->q0), 3, 6);
  expectRank(partitionAt(plain_->model, plain_->q0), 2, 3);
}

TEST_F(RedundantParallelogramTest, FollowsTheClosedFormKinematics) {
  // The closure is held to ≤ 1e-9 m on cranks of 0.4 m: the angle relations hold to a few 1e-9 rad.
  const Trajectory& t = redundant_->coarse;
  EXPECT_LE(t.statistics.max_closure_error, 1e-9);
  const Eigen::VectorXd crank1 = coordinate(t, 0);
  EXPECT_LE(maxDifference(coordinate(t, 2), crank1), 1e-8) << "crank 2 parallel to crank 1";
  EXPECT_LE(maxDifference(coordinate(t, 3), crank1), 1e-8) << "crank 3 parallel to crank 1";
  EXPECT_LE(maxDifference(-coordinate(t, 1), crank1), 1e-8) << "coupler does not rotate";
  EXPECT_GT(crank1.maxCoeff() - crank1.minCoeff(), 60.0 * kDegree) << "the linkage should swing";
}

TEST_F(RedundantParallelogramTest, RedundantCrankDoesNotChangeTheMotion) {
  // Same energy functions (see parallelogram()), same step: the Newmark solutions agree up to the
  // Newton tolerance accumulated over the run.
  EXPECT_LE(maxDifference(coordinate(redundant_->coarse, 0), coordinate(plain_->coarse, 0)), 1e-8);
}

TEST_F(RedundantParallelogramTest, SwingMatchesTheCompoundPendulumToSecondOrder) {
  // Pendulum of small-amplitude frequency ω = √(g·1.44/0.512) ≈ 5.3 rad/s swinging ±50°: trapezoidal
  // phase error ≈ (ωh)²/12 · ωt · amplitude ≈ 2.3e-6 · 16 · 0.87 ≈ 3e-5 rad at h = 1 ms; we allow
  // 1e-4 rad, and halving h must divide the error by ≈ 4 (accepted: ≥ 3).
  const Eigen::VectorXd coarse = coordinate(redundant_->coarse, 0);
  const Eigen::VectorXd fine = coordinate(redundant_->fine, 0);
  const auto reference = [](double step, Eigen::Index count) {
    return integrateRk4(parallelogramCrankAcceleration, kParallelCrank0, 0.0, step, count);
  };
  const double coarse_error = maxDifference(coarse, reference(kStep, coarse.size()));
  const double fine_error = maxDifference(fine, reference(0.5 * kStep, fine.size()));
  EXPECT_LE(coarse_error, 1e-4);
  EXPECT_GE(coarse_error / fine_error, 3.0) << "h: " << coarse_error << " rad, h/2: " << fine_error << " rad";
}

}  // namespace
}  // namespace mbsopt
