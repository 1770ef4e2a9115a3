// Timings of the dynamics core: one residual, the AD tangent matrices, the constraint Jacobian, one
// Newmark step and a whole simulation on the tramway scene; residual and tangents on a planar chain
// of N links, and one Newmark step of that chain closed into a loop, to show how the cost grows
// with the number of coordinates; residual and tangents of a spatial chain on ball joints, in
// rotation vectors (`ball`) and in Cardan angles (`spherical`, three revolutes), the chart's cost.
//
// Residual/tangent timings use a state from a short simulated run (moving, loaded, mid-curve), not
// zeros, so no branch or AD derivative is trivially empty.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/algorithms/tangent.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/design/chain_scenes.hpp"
#include "mbsopt/design/tramway.hpp"

namespace mbsopt {
namespace {

/// A scene together with one state (q, v, a, λ at time t) reached by integrating it for a while.
struct SceneState {
  Scene scene;
  Eigen::VectorXd q, v, a, lambda;
  double t = 0.0;
};

SceneState runFor(Scene scene, double duration) {
  SceneState state{std::move(scene), {}, {}, {}, {}, 0.0};
  NewmarkIntegrator integrator(state.scene.model, state.scene.settings);
  integrator.initialize(state.scene.q0, state.scene.v0);
  const long steps = std::lround(duration / state.scene.settings.step);
  for (long k = 0; k < steps; ++k) integrator.step();
  state.q = integrator.q();
  state.v = integrator.v();
  state.a = integrator.a();
  state.lambda = integrator.lambda();
  state.t = integrator.time();
  return state;
}

/// The tramway 3 s into the run: bogie 1 is in the curve (it enters at t ≈ 0.5 s).
const SceneState& tramwayState() {
  static const SceneState state = runFor(tramwayScene(), 3.0);
  return state;
}

/// Chain state after 0.2 s of free swinging, one per size (built on first use, kept alive).
const SceneState& chainState(int links) {
  static std::map<int, SceneState> states;
  auto it = states.find(links);
  if (it == states.end()) it = states.emplace(links, runFor(planarChainScene(links), 0.2)).first;
  return it->second;
}

// ---- generic kernels, timed on any scene state ----

void timeResidual(benchmark::State& bench, const SceneState& s) {
  Workspace<double> ws(s.scene.model);
  Eigen::VectorXd f;
  for (auto _ : bench) {
    residual(s.scene.model, ws, s.q, s.v, s.a, s.lambda, s.t, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  bench.counters["coordinates"] = static_cast<double>(s.scene.model.coordinateCount());
}

void timeTangentMatrices(benchmark::State& bench, const SceneState& s) {
  Workspace<AdScalar> ws(s.scene.model);
  TangentMatrices out;
  for (auto _ : bench) {
    tangentMatrices(s.scene.model, ws, s.q, s.v, s.a, s.lambda, s.t, out);
    benchmark::DoNotOptimize(out.stiffness.data());
    benchmark::ClobberMemory();
  }
  bench.counters["coordinates"] = static_cast<double>(s.scene.model.coordinateCount());
}

/// One Newmark step per iteration, from the scene's start; the run restarts (not timed) when its end
/// is reached. Counts the Newton iterations per step.
void timeNewmarkSteps(benchmark::State& bench, const Scene& scene) {
  NewmarkIntegrator integrator(scene.model, scene.settings);
  integrator.initialize(scene.q0, scene.v0);
  const double last_start = scene.settings.end_time - scene.settings.step;
  long newton_iterations = 0;
  for (auto _ : bench) {
    if (integrator.time() >= last_start) {
      bench.PauseTiming();
      integrator.initialize(scene.q0, scene.v0);
      bench.ResumeTiming();
    }
    integrator.step();
    newton_iterations += integrator.lastNewtonIterations();
  }
  bench.counters["newton/step"] =
      benchmark::Counter(static_cast<double>(newton_iterations), benchmark::Counter::kAvgIterations);
  // Factorizations of the reduced matrix per step since the last initialize(): 1 while Newton
  // reuses the projections' (J = M), 2 once J has its tangent part.
  const IntegratorStatistics& statistics = integrator.statistics();
  bench.counters["factorizations/step"] =
      static_cast<double>(statistics.factorizations) / static_cast<double>(std::max(1L, statistics.steps));
}

// ---- tramway ----

void BM_TramwayResidual(benchmark::State& bench) { timeResidual(bench, tramwayState()); }
BENCHMARK(BM_TramwayResidual);

void BM_TramwayTangentMatrices(benchmark::State& bench) { timeTangentMatrices(bench, tramwayState()); }
BENCHMARK(BM_TramwayTangentMatrices);

void BM_TramwayConstraintJacobian(benchmark::State& bench) {
  const SceneState& s = tramwayState();
  Workspace<double> ws(s.scene.model);
  Eigen::VectorXd b;
  Eigen::MatrixXd B;
  for (auto _ : bench) {
    constraintJacobian(s.scene.model, ws, s.q, b, B);
    benchmark::DoNotOptimize(B.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_TramwayConstraintJacobian);

void BM_TramwayNewmarkStep(benchmark::State& bench) { timeNewmarkSteps(bench, tramwayState().scene); }
BENCHMARK(BM_TramwayNewmarkStep);

/// accept_by_rate 0: Newton converged at every step (the default); 1: first iterates accepted by the
/// measured contraction rate (NewmarkSettings::accept_by_contraction_rate). kept_buffers 0: a new
/// Trajectory per run, whose pages the kernel maps and zeroes as the run first writes them; 1: the
/// run writes into the last run's Trajectory (simulate's output argument), as the optimizers'
/// evaluations do (DesignNlp's spare buffers).
void BM_TramwaySimulation(benchmark::State& bench) {
  const Scene& scene = tramwayState().scene;  // 12 s at h = 1 ms
  NewmarkSettings settings = scene.settings;
  settings.accept_by_contraction_rate = bench.range(0) == 1;
  const bool kept_buffers = bench.range(1) == 1;
  IntegratorStatistics statistics;
  Trajectory kept;
  for (auto _ : bench) {
    NewmarkIntegrator integrator(scene.model, settings);
    if (kept_buffers) {
      integrator.simulate(scene.q0, scene.v0, kept, {});
      benchmark::DoNotOptimize(kept.q.data());
      statistics = kept.statistics;
    } else {
      const Trajectory trajectory = integrator.simulate(scene.q0, scene.v0);
      benchmark::DoNotOptimize(trajectory.q.data());
      statistics = trajectory.statistics;
    }
  }
  bench.counters["steps"] = static_cast<double>(statistics.steps);
  bench.counters["newton/step"] =
      static_cast<double>(statistics.newton_iterations) / static_cast<double>(statistics.steps);
  bench.counters["jacobians"] = static_cast<double>(statistics.jacobian_updates);
}
BENCHMARK(BM_TramwaySimulation)
    ->ArgNames({"accept_by_rate", "kept_buffers"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond);

// ---- a spatial chain of four links on ball joints ----

/// Four links hanging on ball joints, in rotation vectors (Model::addBallJoint) or in Cardan angles
/// (three revolutes about x, y', z''), thrown about all three axes; its state after 0.2 s.
const SceneState& ballChainState(bool rotation_vectors) {
  static std::map<bool, SceneState> states;
  auto it = states.find(rotation_vectors);
  if (it != states.end()) return it->second;
  Scene scene;
  Model& m = scene.model;
  m.setGravity(Eigen::Vector3d(0.0, 0.0, -9.81));
  FrameIndex tip = Model::ground;
  for (int i = 0; i < 4; ++i) {
    const std::string id = std::to_string(i);
    const std::array<std::string, 3> names{"ball" + id + "_x", "ball" + id + "_y", "ball" + id + "_z"};
    FrameIndex link = tip;
    if (rotation_vectors) link = m.addBallJoint(names, tip);
    else
      for (int axis = 0; axis < 3; ++axis) link = m.addRevolute(names[static_cast<std::size_t>(axis)], link, Eigen::Vector3d::Unit(axis));
    m.addBody("link" + id, link, 1.5, Eigen::Vector3d(0.02, 0.01, -0.25), Eigen::Vector3d(0.03, 0.028, 0.004).asDiagonal());
    tip = m.addOffset("tip" + id, link, Eigen::Vector3d(0.0, 0.0, -0.5));
  }
  scene.q0 = Eigen::VectorXd::Zero(m.coordinateCount());
  scene.v0 = Eigen::VectorXd::LinSpaced(m.coordinateCount(), -2.0, 2.0);
  return states.emplace(rotation_vectors, runFor(std::move(scene), 0.2)).first->second;
}

void BM_BallChainResidual(benchmark::State& bench) { timeResidual(bench, ballChainState(bench.range(0) != 0)); }
BENCHMARK(BM_BallChainResidual)->ArgName("rotation_vectors")->Arg(0)->Arg(1);

void BM_BallChainTangentMatrices(benchmark::State& bench) {
  timeTangentMatrices(bench, ballChainState(bench.range(0) != 0));
}
BENCHMARK(BM_BallChainTangentMatrices)->ArgName("rotation_vectors")->Arg(0)->Arg(1);

// ---- planar chain of N links ----

void BM_ChainResidual(benchmark::State& bench) {
  const int links = static_cast<int>(bench.range(0));
  timeResidual(bench, chainState(links));
  bench.SetComplexityN(links);
}
BENCHMARK(BM_ChainResidual)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Complexity();

void BM_ChainTangentMatrices(benchmark::State& bench) {
  const int links = static_cast<int>(bench.range(0));
  timeTangentMatrices(bench, chainState(links));
  bench.SetComplexityN(links);
}
BENCHMARK(BM_ChainTangentMatrices)->Arg(4)->Arg(8)->Arg(16)->Arg(32)->Complexity();

/// One Newmark step of the open chain (no loop: Newton's target is its tolerance, and its start
/// the degree-6 least-squares extrapolation, newton_predictor.hpp, once 12 steps are known; the
/// run restarts at its end, 1 s, so 11 steps in 1000 start from a shorter extrapolation).
void BM_ChainNewmarkStep(benchmark::State& bench) {
  timeNewmarkSteps(bench, planarChainScene(static_cast<int>(bench.range(0))));
}
BENCHMARK(BM_ChainNewmarkStep)->Arg(8)->Arg(32)->Unit(benchmark::kMicrosecond);

/// One Newmark step of the closed chain (position-level closure, the defaults): Newton on the
/// augmented system, B and its SVD, the projections.
void BM_ClosedChainNewmarkStep(benchmark::State& bench) {
  const int links = static_cast<int>(bench.range(0));
  timeNewmarkSteps(bench, closedPlanarChainScene(links));
  bench.SetComplexityN(links);
}
BENCHMARK(BM_ClosedChainNewmarkStep)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Complexity()->Unit(benchmark::kMicrosecond);

/// The same step with M factored one way for every size (NewmarkSettings::articulated_mass_from):
/// 0, CRBA and the LU of V₂ᵀMV₂ (O(n³)); 1, the articulated-body recursion and the range-space
/// solves (O(n)). The crossover sets the default.
void BM_ClosedChainMassFactorization(benchmark::State& bench) {
  const int links = static_cast<int>(bench.range(0));
  Scene scene = closedPlanarChainScene(links);
  scene.settings.articulated_mass_from = bench.range(1) == 1 ? 0 : std::numeric_limits<int>::max();
  timeNewmarkSteps(bench, scene);
}
BENCHMARK(BM_ClosedChainMassFactorization)
    ->ArgNames({"links", "recursive"})
    ->ArgsProduct({{8, 12, 16, 24, 32, 64}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mbsopt

BENCHMARK_MAIN();
