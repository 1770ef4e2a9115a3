// Timings of the design gradients on the tramway problem (docs/tramway.md, the paper's ⟨⟩
// formulation with b5 = 2 m/s² so the a_lat constraints are active): one simulation with its
// functionals, then the cost's and all constraints' gradients by each method. Every gradient
// benchmark includes its own simulation; the counter `over_simulation` is (gradient − simulation) /
// simulation (the targets were adjoint ≤ 1.0, direct ≤ 0.3 per design variable). Each
// iteration times a plain simulation (evaluateDesign) just before its gradient, outside the
// iteration's time, and the counter is the median over the iterations of that pair's ratio: on a
// shared machine whose speed drifts by ±30 % within minutes, a simulation timed once at start-up
// put the same gradient at 0.7 or 1.5 simulations over one from one run to the next.
// Adjoint and direct run with 1 and 2 threads for their step derivatives (`jobs`): the first is
// the method's cost, the second its wall time on two cores. With `variables:8` the two track
// guidances' stiffness and damping are design variables too. BM_TramwayStepDerivatives times what
// adjoint and direct compute at each time point before their sweep, against a simulated step.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "mbsopt/sensitivity/continuous_adjoint.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"
#include "mbsopt/design/tramway.hpp"

namespace mbsopt {
namespace {

struct TramwayProblem {
  DesignProblem problem = tramwayDesignProblem();
  std::vector<ConstraintFunctional> functionals;
  Eigen::VectorXd x;

  /// The paper's 4 variables, or 8 with the two track guidances' stiffness and damping (bounds ±50 %
  /// around their values): force parameters that take no AD direction (f is linear in them).
  explicit TramwayProblem(int variables) {
    problem.design.artificial.initial = 2.0;
    if (variables == 8)
      for (const char* name : {"bogie1_guidance.k", "bogie1_guidance.c", "bogie2_guidance.k", "bogie2_guidance.c"}) {
        const double value = problem.scene.model.parameter(name);
        problem.design.variables.push_back(designVariable(problem.scene.model, name, 0.5 * value, 1.5 * value, value));
      }
    functionals = transcribe(problem);
    x = initialPoint(problem);
  }

  /// The seconds of one plain simulation with its functionals, the unit of `over_simulation`.
  double timeSimulation() const {
    return secondsOf([&] { benchmark::DoNotOptimize(evaluateDesign(problem, functionals, x)); });
  }

  template <class Work>
  static double secondsOf(Work&& work) {
    const auto start = std::chrono::steady_clock::now();
    work();
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    return elapsed.count();
  }
};

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

const TramwayProblem& tramway(int variables = 4) {
  static const TramwayProblem paper(4), with_guidance(8);
  return variables == 8 ? with_guidance : paper;
}

/// Times `method` on the tramway problem with `variables` design variables; `over_simulation`
/// compares each run with a plain simulation timed just before it.
template <class Method>
void timeGradient(benchmark::State& state, Method method, int variables = 4) {
  const TramwayProblem& t = tramway(variables);
  std::vector<double> over_simulation;
  for (auto _ : state) {
    const double simulation = t.timeSimulation();
    const double gradient = TramwayProblem::secondsOf([&] { benchmark::DoNotOptimize(method(t)); });
    state.SetIterationTime(gradient);
    over_simulation.push_back((gradient - simulation) / simulation);
  }
  state.counters["over_simulation"] = median(over_simulation);
  state.counters["design_variables"] = static_cast<double>(t.problem.design.variables.size());
}

void BM_TramwaySimulation(benchmark::State& state) {
  const TramwayProblem& t = tramway();
  for (auto _ : state) benchmark::DoNotOptimize(evaluateDesign(t.problem, t.functionals, t.x).cost);
}
BENCHMARK(BM_TramwaySimulation)->Unit(benchmark::kMillisecond);

/// The runs of an exact method: the paper's 4 variables on 1 and 2 threads, 8 variables on one.
void exactGradientRuns(benchmark::internal::Benchmark* runs) {
  runs->ArgNames({"jobs", "variables"})->Args({1, 4})->Args({2, 4})->Args({1, 8});
  runs->UseManualTime()->Unit(benchmark::kMillisecond);
}

void BM_TramwayGradientAdjoint(benchmark::State& state) {
  const int jobs = static_cast<int>(state.range(0));
  timeGradient(
      state, [jobs](const TramwayProblem& t) { return adjointGradient(t.problem, t.functionals, t.x, nullptr, jobs); },
      static_cast<int>(state.range(1)));
}
BENCHMARK(BM_TramwayGradientAdjoint)->Apply(exactGradientRuns);

void BM_TramwayGradientContinuousAdjoint(benchmark::State& state) {
  timeGradient(state, [](const TramwayProblem& t) { return continuousAdjointGradient(t.problem, t.functionals, t.x); });
}
BENCHMARK(BM_TramwayGradientContinuousAdjoint)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_TramwayGradientDirect(benchmark::State& state) {
  const int jobs = static_cast<int>(state.range(0));
  timeGradient(
      state, [jobs](const TramwayProblem& t) { return directGradient(t.problem, t.functionals, t.x, nullptr, jobs); },
      static_cast<int>(state.range(1)));
}
BENCHMARK(BM_TramwayGradientDirect)->Apply(exactGradientRuns);

/// What the exact methods compute at each time point before their sweep (TrajectoryDerivatives::
/// PointStream: M, C_T, K_T, ∂f/∂b, the closure and projection derivatives, the sensor seeds), at
/// every point of the tramway trajectory on one thread. `per_point_us`, and `over_step`: the same
/// over one step's share of a simulation timed just before (median over the iterations), which an
/// adjoint at ≤ 1 simulation needs well below 1.
void BM_TramwayStepDerivatives(benchmark::State& state) {
  const TramwayProblem& t = tramway();
  TrajectoryDerivatives derivatives(t.problem, t.functionals, t.x);
  const Eigen::Index last = derivatives.timePoints() - 1;  // points 1 … last, one per step
  double total = 0.0;
  std::vector<double> over_step;
  for (auto _ : state) {
    const double simulation = t.timeSimulation();
    const double seconds = TramwayProblem::secondsOf([&] {
      TrajectoryDerivatives::PointStream points(derivatives, 1, last, 1);
      for (Eigen::Index k = 1; k <= last; ++k) benchmark::DoNotOptimize(&points.next());
    });
    total += seconds;
    state.SetIterationTime(seconds);
    over_step.push_back(seconds / simulation);  // (seconds / last) / (simulation / last)
  }
  state.counters["per_point_us"] = total / static_cast<double>(state.iterations()) / static_cast<double>(last) * 1e6;
  state.counters["over_step"] = median(over_step);
}
BENCHMARK(BM_TramwayStepDerivatives)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_TramwayGradientCentralDifferences(benchmark::State& state) {
  timeGradient(state, [](const TramwayProblem& t) {
    return finiteDifferenceGradient(t.problem, t.functionals, t.x, 1e-5, true);
  });
}
BENCHMARK(BM_TramwayGradientCentralDifferences)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mbsopt

BENCHMARK_MAIN();
