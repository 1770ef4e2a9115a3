// Simulates a scene, runs an optimizer, an optimisation study and a precision study through the
// installed package's headers and libraries, and checks each against closed forms. Exit status 0
// when all hold; otherwise it says which failed.
//
// The scene: a unit mass on a spring, x(0) = 1, ẋ(0) = 0. The trapezoidal Newmark rule turns
// (x, ẋ/ω) by θ = 2 atan(ωh/2) per step, so x(t_n) = cos(n θ) exactly on its grid: the simulation
// must match that to Newton's round-off, and a run's error against the exact motion cos(ω t) is
// max over the compared times of |cos(t θ/h) − cos(ω t)|. The design: minimise the RMS of x over 1 s
// under min x ≥ −0.5, whose optimum has x(1 s) = −0.5, i.e. ω_h = (2/h) atan(ωh/2) = 2π/3, so
// k* = ω² = ((2/h) tan(π h/3))².
#include <mbsopt/integrators/newmark.hpp>
#include <mbsopt/optimizers/optimizer.hpp>
#include <mbsopt/io/scene_file.hpp>
#include <mbsopt/design/design_nlp.hpp>
#include <mbsopt/design/optimization_run.hpp>
#include <mbsopt/design/precision_study.hpp>
#include <mbsopt/design/run_record.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace {

const char* const kScene = R"(settings: {step: 1.0e-3, end_time: 1}
elements:
  - {name: x, type: prismatic, parent: ground, axis: [1, 0, 0], q0: 1}
bodies:
  - {name: mass, frame: x, mass: 1, Ixx: 1, Iyy: 1, Izz: 1}
forces:
  - {name: spring, type: joint_spring_damper, joint: x, k: 2}
sensors:
  - {name: position, type: joint, joint: x, quantity: position}
design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: position, of: rms}
  artificial: {initial: 1, lower: -2, upper: 2}
  transcription: {measure: grid_max}
  constraints:
    - {sensor: position, of: min, bound: -0.5}
)";

bool check(bool holds, const char* what, double value, double expected) {
  std::printf("%s: %s (%.12g, expected %.12g)\n", holds ? "ok" : "FAILED", what, value, expected);
  return holds;
}

}  // namespace

int main() {
  using namespace mbsopt;
  const SceneSource source{"consumer.yaml", kScene};
  const double h = 1e-3;

  const LoadedScene loaded = loadScene(source);
  const Scene& scene = loaded.scene;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const Eigen::Index last = trajectory.time.size() - 1;
  const double theta = 2.0 * std::atan(std::sqrt(2.0) * h / 2.0);
  const double expected_x = std::cos(static_cast<double>(last) * theta);
  bool ok = check(std::abs(trajectory.q(0, last) - expected_x) <= 1e-9, "simulated x(1 s)", trajectory.q(0, last),
                  expected_x);

  DesignNlp nlp(loadDesignProblem(source), "adjoint");
  const OptimizerResult result = minimize("slsqp", nlp, OptimizerOptions{});
  const double k = result.x[0] * nlp.problem().design.variables[0].scale;
  const double expected_k = std::pow(2.0 / h * std::tan(std::numbers::pi * h / 3.0), 2);
  ok &= check(result.status == OptimizerStatus::Converged, ("SLSQP: " + result.message).c_str(), result.cost, result.cost);
  ok &= check(std::abs(k - expected_k) <= 1e-5 * expected_k, "optimal spring.k", k, expected_k);

  // The same optimum as a study reports it: the design in SI units, the verdicts, the JSON record.
  RunChoice choice;
  choice.optimizer = "slsqp";
  const OptimizationRun run = runOptimization(loadDesignProblem(source), choice, {});
  const nlohmann::json record = toJson(run, source.path);
  ok &= check(feasible(run) && record["feasible"].get<bool>(), "the study's final design meets its constraint",
              run.verdicts.at(0).value, -0.5);
  ok &= check(std::abs(run.design.at(0) - expected_k) <= 1e-5 * expected_k, "the study's spring.k [N/m]",
              record["design"][0].get<double>(), expected_k);

  // A precision study of Newmark at two steps against an extrapolated reference on their common grid:
  // each run's error is the closed form's, whose ratio over a halving is that of a second-order rule.
  const std::vector<double> steps{2e-3, 1e-3};
  const Eigen::VectorXd times = commonGridTimes(steps, scene.settings.end_time);
  const ReferenceSolution reference = referenceRun(scene, 1e-3, 4, times, {"x"});
  const double omega = std::sqrt(2.0);
  for (const double step : steps) {
    const PrecisionRun measured = measureIntegratorRun(scene, "newmark", step, 0.0, 1, reference, 1);
    const double theta = 2.0 * std::atan(omega * step / 2.0);
    double expected_error = 0.0;
    for (const double t : times) expected_error = std::max(expected_error, std::abs(std::cos(t * theta / step) - std::cos(omega * t)));
    // The reference's own error (extrapolation of 4 runs, O(h⁸)) and Newton's round-off are below 1e-12.
    ok &= check(!measured.failed && std::abs(measured.error - expected_error) <= 1e-9,
                ("Newmark's error at h = " + std::to_string(step) + " s").c_str(), measured.error, expected_error);
  }
  return ok ? 0 : 1;
}
