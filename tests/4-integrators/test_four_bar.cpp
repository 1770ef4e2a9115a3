// Planar four-bar linkage (Grashof crank-rocker) under gravity, no damping, closed by a spatial
// revolute cut joint: loop closure along the whole simulation and conservation of mechanical energy
// by the trapezoidal rule (Newmark β = 1/4, γ = 1/2).
#include <gtest/gtest.h>

#include "tests/mechanical_energy.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/assembly.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {
namespace {

using test::Energy;
using test::mechanicalEnergy;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// Link lengths [m]: shortest + longest = 0.3 + 1.0 ≤ 0.8 + 1.0 = the other two (Grashof) and the
// shortest link is the crank, so the crank turns fully relative to the ground and the rocker
// oscillates; the linkage never reaches a dead point, so the loop stays regular (rank 2) throughout.
constexpr double kGround = 1.0, kCrank = 0.3, kCoupler = 1.0, kRocker = 0.8;
constexpr double kLinearDensity = 2.0;  // [kg/m]
constexpr double kBarWidth = 0.03;      // square cross-section [m]
constexpr double kEndTime = 10.0;
constexpr double kStep = 1e-3;
constexpr double kInitialCrankRate = 7.0;  // [rad/s] before assemble() projects it onto the loop

/// Uniform slender bar along x from the frame origin: centre of mass and inertia about it.
void addBar(Model& model, const std::string& name, FrameIndex frame, double length) {
  const double mass = kLinearDensity * length;
  const double axial = mass * kBarWidth * kBarWidth / 6.0;
  const double transverse = mass * (length * length + kBarWidth * kBarWidth) / 12.0;
  model.addBody(name, frame, mass, Eigen::Vector3d(0.5 * length, 0.0, 0.0),
                Eigen::Vector3d(axial, transverse, transverse).asDiagonal());
}

/// Coordinates: crank angle (ground), coupler angle relative to the crank, rocker angle (ground).
Model crankRocker() {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Model model;
  const FrameIndex crank = model.addRevolute("crank", Model::ground, z);
  addBar(model, "crank_bar", crank, kCrank);
  const FrameIndex crank_tip = model.addOffset("crank_tip", crank, kCrank * Eigen::Vector3d::UnitX());
  const FrameIndex coupler = model.addRevolute("coupler", crank_tip, z);
  addBar(model, "coupler_bar", coupler, kCoupler);
  const FrameIndex coupler_tip = model.addOffset("coupler_tip", coupler, kCoupler * Eigen::Vector3d::UnitX());
  const FrameIndex rocker_pivot = model.addOffset("rocker_pivot", Model::ground, kGround * Eigen::Vector3d::UnitX());
  const FrameIndex rocker = model.addRevolute("rocker", rocker_pivot, z);
  addBar(model, "rocker_bar", rocker, kRocker);
  const FrameIndex rocker_tip = model.addOffset("rocker_tip", rocker, kRocker * Eigen::Vector3d::UnitX());
  model.addRevoluteCut("loop", coupler_tip, rocker_tip, z, z);  // 5 equations, 2 independent in the plane
  model.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
  return model;
}

struct EnergyHistory {
  Eigen::VectorXd deviation;  ///< |E(t) − E(0)|
  double kinetic_scale = 0.0;  ///< max T over the run: the energy scale, independent of the potential's datum
  double maxRelativeDeviation(Eigen::Index first, Eigen::Index count) const {
    return deviation.segment(first, count).maxCoeff() / kinetic_scale;
  }
};

EnergyHistory energyHistory(const Model& model, const Trajectory& trajectory) {
  Workspace<double> ws(model);
  const Eigen::Index points = trajectory.time.size();
  EnergyHistory history;
  history.deviation.resize(points);
  const double initial = mechanicalEnergy(model, ws, trajectory.q.col(0), trajectory.v.col(0)).total();
  for (Eigen::Index k = 0; k < points; ++k) {
    const Energy e = mechanicalEnergy(model, ws, trajectory.q.col(k), trajectory.v.col(k));
    history.deviation[k] = std::abs(e.total() - initial);
    history.kinetic_scale = std::max(history.kinetic_scale, e.kinetic);
  }
  return history;
}

struct FourBarRun {
  Model model = crankRocker();
  Eigen::VectorXd q0, v0;
  AssemblyReport assembly;
  Trajectory coarse, fine;  ///< h and h/2

  FourBarRun() : q0(3), v0(3) {
    // Rough guess of the elbow-up branch at a crank angle of 60°; assemble() closes the loop.
    q0 << 60.0 * kDegree, -27.0 * kDegree, 91.0 * kDegree;
    v0 << kInitialCrankRate, 0.0, 0.0;
    assembly = assemble(model, q0, v0, 0.0);
    coarse = simulate(kStep);
    fine = simulate(0.5 * kStep);
  }
  Trajectory simulate(double step) const {
    NewmarkSettings settings;
    settings.step = step;
    settings.end_time = kEndTime;
    return NewmarkIntegrator(model, settings).simulate(q0, v0);
  }
};

class FourBarTest : public ::testing::Test {
 protected:
  /// The simulations are shared by the tests of the suite (they are the expensive part).
  static void SetUpTestSuite() { run_ = std::make_unique<FourBarRun>(); }
  static void TearDownTestSuite() { run_.reset(); }
  static inline std::unique_ptr<FourBarRun> run_;
};

TEST_F(FourBarTest, AssemblyClosesTheLoopFromARoughGuess) {
  EXPECT_LE(run_->assembly.closure_error, 1e-12);
  EXPECT_GT(run_->assembly.position_correction, 1e-3);  // the guess was off by ~0.5°: assemble did real work
  EXPECT_NEAR(run_->q0[0], 60.0 * kDegree, 2.0 * kDegree);  // stayed on the intended branch, near the guess
}

TEST_F(FourBarTest, CrankTurnsOverSoTheWholeCycleIsExercised) {
  const Eigen::VectorXd crank = run_->coarse.q.row(0);
  EXPECT_GT(crank.maxCoeff() - crank.minCoeff(), 4.0 * kPi);  // at least two revolutions in 10 s
}

TEST_F(FourBarTest, ClosureErrorStaysBelowOneNanometreAtEveryStep) {
  // Position-level closure is solved by Newton to ‖Δq̈‖ ≤ 1e-10 (1 + ‖q̈‖), i.e. b ≈ βh²·1e-10·… ≪ 1e-9 m.
  ASSERT_EQ(run_->coarse.closure_error.size(), static_cast<Eigen::Index>(std::lround(kEndTime / kStep)) + 1);
  Eigen::Index worst = 0;
  const double largest = run_->coarse.closure_error.maxCoeff(&worst);
  EXPECT_LE(largest, 1e-9) << "at t = " << run_->coarse.time[worst] << " s";
  EXPECT_LE(run_->coarse.statistics.max_closure_error, 1e-9);
}

TEST_F(FourBarTest, EnergyErrorIsSmallAndSecondOrderInTheStep) {
  // The trapezoidal rule conserves the energy of a linear system exactly and that of a nonlinear
  // conservative one up to a bounded oscillation of relative size O((ωh)²). The joint rates of this
  // run reach ω ≈ 17 rad/s, (ωh)² ≈ 3e-4 at h = 1 ms: we allow 2e-4 of the kinetic-energy scale,
  // and halving h must divide the error by ≈ 4 (accepted: ≥ 3), which a first-order error
  // (numerical dissipation) cannot do.
  const EnergyHistory coarse = energyHistory(run_->model, run_->coarse);
  const EnergyHistory fine = energyHistory(run_->model, run_->fine);
  const double coarse_error = coarse.maxRelativeDeviation(0, coarse.deviation.size());
  const double fine_error = fine.maxRelativeDeviation(0, fine.deviation.size());
  EXPECT_LE(coarse_error, 2e-4);
  EXPECT_GE(coarse_error / fine_error, 3.0) << "h: " << coarse_error << ", h/2: " << fine_error;
}

TEST_F(FourBarTest, EnergyDoesNotDrift) {
  // A bounded oscillating error repeats cycle after cycle (a quarter, 2.5 s, spans more than one
  // crank revolution of ≈ 2.2 s):
  // a drift (numerical dissipation or growth, e.g. from the constraint projections) would make the
  // last quarter of the run markedly worse than the first.
  const EnergyHistory history = energyHistory(run_->model, run_->coarse);
  const Eigen::Index quarter = history.deviation.size() / 4;
  const double first = history.maxRelativeDeviation(0, quarter);
  const double last = history.maxRelativeDeviation(history.deviation.size() - quarter, quarter);
  EXPECT_LE(last, 1.5 * first) << "first quarter " << first << ", last quarter " << last;
}

}  // namespace
}  // namespace mbsopt
