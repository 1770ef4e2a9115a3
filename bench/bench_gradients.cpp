// Timings of the design gradients on the tramway problem (docs/tramway.md, the paper's ⟨⟩
// formulation with b5 = 2 m/s² so the a_lat constraints are active): one simulation with its
// functionals, then the cost's and all constraints' gradients by each method. Every gradient
// benchmark includes its own simulation; the counter `over_simulation` is (gradient − simulation) /
// simulation, the measure (targets: adjoint ≤ 1.0, direct ≤ 0.3 per design variable).
// Adjoint and direct run with 1 and 2 threads for their step derivatives (`jobs`): the first is
// the method's cost, the second its wall time on two cores.
#include <benchmark/benchmark.h>

#include <chrono>

#include "problems/tramway.hpp"
#include "sensitivity/continuous_adjoint.hpp"
#include "sensitivity/design_evaluation.hpp"
#include "sensitivity/direct_sensitivity.hpp"
#include "sensitivity/discrete_adjoint.hpp"

namespace mbsopt {
namespace {

struct TramwayProblem {
  DesignProblem problem = tramwayDesignProblem();
  std::vector<ConstraintFunctional> functionals;
  Eigen::VectorXd x;
  double simulation_seconds = 0.0;  ///< the fastest of a few plain runs, for `over_simulation`

  TramwayProblem() {
    problem.design.artificial.initial = 2.0;
    functionals = transcribe(problem);
    x = initialPoint(problem);
    simulation_seconds = 1e300;
    for (int run = 0; run < 5; ++run) {
      const auto start = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(evaluateDesign(problem, functionals, x));
      const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
      simulation_seconds = std::min(simulation_seconds, elapsed.count());
    }
  }
};

const TramwayProblem& tramway() {
  static const TramwayProblem instance;
  return instance;
}

/// Times `method` on the tramway problem; `over_simulation` compares it with the plain simulation.
template <class Method>
void timeGradient(benchmark::State& state, Method method) {
  const TramwayProblem& t = tramway();
  double total = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(method(t));
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    total += elapsed.count();
    state.SetIterationTime(elapsed.count());
  }
  const double mean = total / static_cast<double>(state.iterations());
  state.counters["over_simulation"] = (mean - t.simulation_seconds) / t.simulation_seconds;
  state.counters["design_variables"] = static_cast<double>(t.problem.design.variables.size());
}

void BM_TramwaySimulation(benchmark::State& state) {
  const TramwayProblem& t = tramway();
  for (auto _ : state) benchmark::DoNotOptimize(evaluateDesign(t.problem, t.functionals, t.x).cost);
}
BENCHMARK(BM_TramwaySimulation)->Unit(benchmark::kMillisecond);

void BM_TramwayGradientAdjoint(benchmark::State& state) {
  const int jobs = static_cast<int>(state.range(0));
  timeGradient(state, [jobs](const TramwayProblem& t) { return adjointGradient(t.problem, t.functionals, t.x, nullptr, jobs); });
}
BENCHMARK(BM_TramwayGradientAdjoint)->ArgName("jobs")->Arg(1)->Arg(2)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_TramwayGradientContinuousAdjoint(benchmark::State& state) {
  timeGradient(state, [](const TramwayProblem& t) { return continuousAdjointGradient(t.problem, t.functionals, t.x); });
}
BENCHMARK(BM_TramwayGradientContinuousAdjoint)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_TramwayGradientDirect(benchmark::State& state) {
  const int jobs = static_cast<int>(state.range(0));
  timeGradient(state, [jobs](const TramwayProblem& t) { return directGradient(t.problem, t.functionals, t.x, nullptr, jobs); });
}
BENCHMARK(BM_TramwayGradientDirect)->ArgName("jobs")->Arg(1)->Arg(2)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_TramwayGradientCentralDifferences(benchmark::State& state) {
  timeGradient(state, [](const TramwayProblem& t) {
    return finiteDifferenceGradient(t.problem, t.functionals, t.x, 1e-5, true);
  });
}
BENCHMARK(BM_TramwayGradientCentralDifferences)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mbsopt

BENCHMARK_MAIN();
