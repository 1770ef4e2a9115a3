// Planar double pendulum: the library's residual and mass matrix against Lagrange's equations
// derived by hand.
//
// Model: revolute q₁ about ground z; an offset d (in body-1 axes) to a second revolute q₂ about z.
// Body i has mass mᵢ, centre of mass cᵢ (in its frame's axes, with an out-of-plane component) and a
// full, non-diagonal inertia tensor about cᵢ. A spring-damper k(q₂ − r) + c q̇₂ acts on the elbow.
// Gravity g = (g_x, g_y, g_z).
//
// Derivation with absolute angles θ₁ = q₁, θ₂ = q₁ + q₂ (θ = T q, T = [1 0; 1 1]). Motion is in the
// xy plane, so only in-plane components matter: z offsets move nothing, rotation about z keeps
// the zz inertia component, and g_z and the products of inertia only load the joints' reaction
// moments (their z-moments vanish). Write R(θ) for the planar rotation, E = R(π/2) (so
// d/dθ R(θ)u = E R(θ)u), cross(a, b) = a_x b_y − a_y b_x, and in ground axes
//     s = R(θ₁)c₁,  u = R(θ₁)d,  w = R(θ₂)c₂,   C = u·w,  S = cross(u, w).
// Centres of mass p₁ = s, p₂ = u + w, so ṗ₁ = θ̇₁Es, ṗ₂ = θ̇₁Eu + θ̇₂Ew and
//     T = ½(m₁|c₁|² + I₁ + m₂|d|²)θ̇₁² + m₂C θ̇₁θ̇₂ + ½(m₂|c₂|² + I₂)θ̇₂²,   V = −m₁g·p₁ − m₂g·p₂.
// With ∂C/∂θ₁ = S and ∂C/∂θ₂ = −S, Lagrange's equations f_θ = M_θθ̈ + c + ∂V/∂θ = 0 read
//     M_θ = [m₁|c₁|² + I₁ + m₂|d|²,  m₂C;  m₂C,  m₂|c₂|² + I₂]
//     c   = (−m₂S θ̇₂²,  +m₂S θ̇₁²)
//     ∂V/∂θ = (−m₁g·Es − m₂g·Eu,  −m₂g·Ew).
// The residual in joint coordinates is the virtual-work projection f_q = Tᵀf_θ plus the elbow
// spring-damper, and M_q = TᵀM_θT.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/algorithms/tangent.hpp"

using namespace mbsopt;

namespace {

struct Link {
  double mass;
  Eigen::Vector3d centre_of_mass;
  Eigen::Matrix3d inertia;  // about the centre of mass
};

struct DoublePendulum {
  Link upper{1.3, {0.35, 0.05, 0.02}, (Eigen::Matrix3d() << 0.020, 0.001, 0.002, 0.001, 0.030, -0.001, 0.002, -0.001, 0.025).finished()};
  Link lower{0.9, {0.40, -0.06, -0.03}, (Eigen::Matrix3d() << 0.012, -0.002, 0.001, -0.002, 0.015, 0.0015, 0.001, 0.0015, 0.018).finished()};
  Eigen::Vector3d elbow_offset{0.8, 0.1, 0.05};  // d, in body-1 axes
  double elbow_stiffness = 15.0, elbow_damping = 0.4, elbow_rest = 0.3;
  Eigen::Vector3d gravity{0.5, -9.81, 0.7};
};

Model buildModel(const DoublePendulum& p) {
  Model model;
  const FrameIndex upper = model.addRevolute("shoulder", Model::ground, Eigen::Vector3d::UnitZ());
  model.addBody("upper_link", upper, p.upper.mass, p.upper.centre_of_mass, p.upper.inertia);
  const FrameIndex elbow = model.addOffset("elbow_offset", upper, p.elbow_offset);
  const FrameIndex lower = model.addRevolute("elbow", elbow, Eigen::Vector3d::UnitZ());
  model.addBody("lower_link", lower, p.lower.mass, p.lower.centre_of_mass, p.lower.inertia);
  model.addJointSpringDamper("elbow_spring", "elbow", p.elbow_stiffness, p.elbow_damping, p.elbow_rest);
  model.setGravity(p.gravity);
  return model;
}

// ---- the hand-derived Lagrangian model ----
Eigen::Vector2d inPlane(const Eigen::Vector3d& v) { return v.head<2>(); }
Eigen::Vector2d rotated(double angle, const Eigen::Vector2d& v) { return Eigen::Rotation2Dd(angle) * v; }
Eigen::Vector2d perpendicular(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }  // E v
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// θ = T q with T = [1 0; 1 1].
const Eigen::Matrix2d kAbsoluteFromRelative = (Eigen::Matrix2d() << 1.0, 0.0, 1.0, 1.0).finished();

struct LagrangeTerms {
  Eigen::Matrix2d mass;  ///< M_q
  Eigen::Vector2d bias;  ///< f_q at q̈ = 0: Coriolis/centrifugal + gravity + elbow spring-damper
};

LagrangeTerms lagrangeTerms(const DoublePendulum& p, const Eigen::Vector2d& q, const Eigen::Vector2d& qd) {
  const Eigen::Matrix2d& T = kAbsoluteFromRelative;
  const Eigen::Vector2d theta = T * q, theta_d = T * qd;
  const double m1 = p.upper.mass, m2 = p.lower.mass;
  const Eigen::Vector2d c1 = inPlane(p.upper.centre_of_mass), c2 = inPlane(p.lower.centre_of_mass);
  const Eigen::Vector2d d = inPlane(p.elbow_offset), g = inPlane(p.gravity);
  const Eigen::Vector2d s = rotated(theta[0], c1), u = rotated(theta[0], d), w = rotated(theta[1], c2);
  const double C = u.dot(w), S = cross(u, w);

  Eigen::Matrix2d mass_theta;
  mass_theta << m1 * c1.squaredNorm() + p.upper.inertia(2, 2) + m2 * d.squaredNorm(), m2 * C,  //
      m2 * C, m2 * c2.squaredNorm() + p.lower.inertia(2, 2);
  const Eigen::Vector2d coriolis(-m2 * S * theta_d[1] * theta_d[1], m2 * S * theta_d[0] * theta_d[0]);
  const Eigen::Vector2d potential_gradient(-m1 * g.dot(perpendicular(s)) - m2 * g.dot(perpendicular(u)),
                                           -m2 * g.dot(perpendicular(w)));
  const Eigen::Vector2d spring(0.0, p.elbow_stiffness * (q[1] - p.elbow_rest) + p.elbow_damping * qd[1]);
  return {T.transpose() * mass_theta * T, T.transpose() * (coriolis + potential_gradient) + spring};
}

Eigen::Vector2d lagrangeAcceleration(const LagrangeTerms& terms) { return terms.mass.ldlt().solve(-terms.bias); }

// ---- random states ----
struct State {
  Eigen::VectorXd q, qd;
};

std::vector<State> randomStates(int count) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-4.0, 4.0);
  std::vector<State> states;
  for (int i = 0; i < count; ++i) {
    State s{Eigen::VectorXd(2), Eigen::VectorXd(2)};
    s.q << angle(rng), angle(rng);
    s.qd << rate(rng), rate(rng);
    states.push_back(s);
  }
  return states;
}

class DoublePendulumTest : public ::testing::Test {
 protected:
  DoublePendulum pendulum;
  Model model = buildModel(pendulum);
  Workspace<double> ws{model};
  Workspace<AdScalar> ad_ws{model};
  const Eigen::VectorXd no_multipliers = Eigen::VectorXd(0);
  const Eigen::VectorXd zero_acceleration = Eigen::VectorXd::Zero(2);
  static constexpr double kTime = 0.0;
};

TEST_F(DoublePendulumTest, CoordinatesAreTheTwoJointAngles) {
  ASSERT_EQ(model.coordinateCount(), 2);
  EXPECT_EQ(model.coordinate("shoulder"), 0);
  EXPECT_EQ(model.coordinate("elbow"), 1);
}

// Both sides are built from the same ~10 O(1) terms in double precision; with a mass matrix of
// condition number < 100 the round-off in q̈ is ~1e-13 relative. 1e-10 leaves room for that and
// catches any wrong term (a missing product of inertia, sign or Coriolis factor is O(1e-2) or more).
TEST_F(DoublePendulumTest, AccelerationsMatchLagrangesEquations) {
  for (const State& state : randomStates(25)) {
    TangentMatrices tangents;
    tangentMatrices(model, ad_ws, state.q, state.qd, zero_acceleration, no_multipliers, kTime, tangents);
    const LagrangeTerms lagrange = lagrangeTerms(pendulum, state.q, state.qd);

    // M is exactly ∂f/∂q̈ and f is linear in q̈, so M q̈ = −f(q̈ = 0).
    EXPECT_LE((tangents.mass - lagrange.mass).cwiseAbs().maxCoeff(), 1e-12 * lagrange.mass.cwiseAbs().maxCoeff())
        << "q = " << state.q.transpose() << "\nlibrary M =\n" << tangents.mass << "\nLagrange M =\n" << lagrange.mass;
    const Eigen::Vector2d library_acceleration = tangents.mass.ldlt().solve(-tangents.residual);
    const Eigen::Vector2d expected = lagrangeAcceleration(lagrange);
    EXPECT_LE((library_acceleration - expected).norm(), 1e-10 * expected.norm())
        << "q = " << state.q.transpose() << ", q̇ = " << state.qd.transpose()
        << "\nlibrary q̈ = " << library_acceleration.transpose() << "\nLagrange q̈ = " << expected.transpose();
  }
}

// f(q̈_Lagrange) is a difference of terms of size |M q̈| and |f(0)|; round-off in each is ~1e-15
// relative, so 1e-9 of their size is a wide but still meaningful bar.
TEST_F(DoublePendulumTest, ResidualVanishesAtLagrangeAccelerations) {
  for (const State& state : randomStates(25)) {
    const LagrangeTerms lagrange = lagrangeTerms(pendulum, state.q, state.qd);
    const Eigen::VectorXd acceleration = lagrangeAcceleration(lagrange);
    Eigen::VectorXd f;
    residual(model, ws, state.q, state.qd, acceleration, no_multipliers, kTime, f);
    ASSERT_EQ(f.size(), 2);
    const double scale = (lagrange.mass * acceleration).cwiseAbs().maxCoeff() + lagrange.bias.cwiseAbs().maxCoeff();
    EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-9 * scale)
        << "q = " << state.q.transpose() << ", q̇ = " << state.qd.transpose() << ", f = " << f.transpose();
  }
}

}  // namespace
