// What every registered integrator (4-integrators/integration.cpp) must do, whatever it is, as
// EveryOptimizer does for the optimizers; instantiated from the registry, so an integrator added
// there is held to it:
// - order: on the undamped oscillator x'' = −ω²x (exact solution cos ωt), a fixed-step integrator's
//   error falls by 2^p over a halving of its step, p its order (Integration::run.order); a
//   variable-step one, whose global error grows as its local tolerance to the power 2/3 (local
//   error ∝ h³, steps ∝ tol^{1/3}), by 8^{2/3} = 4 over a tolerance 8 times smaller;
// - closure: on the four-bar, the loop stays closed at every stored point, to the position
//   closure's round-off;
// - failure outcomes: a loop that no configuration closes ends a fixed-step run with LoopCannotClose
//   at its cut, also when driven by accuracy (no step size is at fault, so it is not retried); a
//   variable-step run, whose steps shrink towards the loop's reach limit t* where the motion is
//   singular, ends there, at t*, with its step too large (its steps below 1e-12 of the run), and
//   driven by accuracy it does not go through either; a prescribed motion that is not finite ends
//   every run at once with CheckFailed;
// - gradients: the exact (adjoint) gradient of a design problem integrated by it equals central
//   differences of the same discrete functional.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/design_nlp.hpp"
#include "tests/integrator_scenes.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

class EveryIntegrator : public testing::TestWithParam<std::string> {
 protected:
  const IntegratorInfo& info() const { return integratorInfo(GetParam()); }
  IntegrationRequest request() const {
    IntegrationRequest r;
    r.integrator.name = GetParam();
    return r;
  }
};

/// The oscillator's run by `integrator` at `step` (a variable-step one at `local_tolerance`).
Integration oscillatorRun(const std::string& integrator, double step, double local_tolerance) {
  Scene scene = test::oscillator(1.0);
  scene.settings.step = step;
  IntegrationRequest request;
  request.integrator.name = integrator;
  request.integrator.local_tolerance = local_tolerance;
  return integrate(scene.model, scene.settings, scene.q0, scene.v0, request);
}

double oscillatorError(const std::string& integrator, double step, double local_tolerance) {
  return test::trueOscillatorError(oscillatorRun(integrator, step, local_tolerance).run.trajectory);
}

TEST_P(EveryIntegrator, ConvergesAtItsOrder) {
  if (info().variable_steps) {
    const double coarse = oscillatorError(GetParam(), 1e-2, 1e-5), fine = oscillatorError(GetParam(), 1e-2, 1.25e-6);
    EXPECT_NEAR(coarse / fine, 4.0, 1.0) << coarse << " " << fine;
    return;
  }
  const Integration coarse_run = oscillatorRun(GetParam(), 0.02, 0.0);
  const int order = coarse_run.run.order;
  const double coarse = test::trueOscillatorError(coarse_run.run.trajectory), fine = oscillatorError(GetParam(), 0.01, 0.0);
  const double expected = std::pow(2.0, order);
  EXPECT_GT(coarse / fine, 0.8 * expected) << "order " << order;
  EXPECT_LT(coarse / fine, 1.25 * expected) << "order " << order;
}

TEST_P(EveryIntegrator, KeepsTheFourBarsLoopClosed) {
  const Scene scene = test::sceneFile("problems/scenes/four_bar.yaml");
  const Integration run = integrate(scene.model, scene.settings, scene.q0, scene.v0, request());
  const Trajectory& t = run.run.trajectory;
  ASSERT_GT(t.time.size(), 1);
  ASSERT_EQ(t.closure_error.size(), t.time.size());
  EXPECT_LT(t.closure_error.maxCoeff(), 1e-10);  // position closure: b(q) at round-off, the links ~1 m
}

TEST_P(EveryIntegrator, EndsWithLoopCannotCloseAtTheCut) {
  // The slider-crank with a rod too short for the crank's drive (test_integrator_errors.cpp).
  const LoadedScene loaded =
      loadScene(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/slider_crank.yaml"),
                {{"conrod_end.translation.x", 0.12}, {"rail.translation.y", 0.05}});
  const Scene& scene = loaded.scene;
  const double t_star = (std::numbers::pi + std::asin(0.7)) / 10.0;  // the rod reaches the rail until then
  for (const bool by_accuracy : {false, true}) {
    IntegrationRequest r = request();
    if (by_accuracy) r.accuracy = ErrorTolerance{1e-6, 0.0};
    if (info().variable_steps) {
      if (by_accuracy) {
        EXPECT_THROW(integrate(scene.model, scene.settings, scene.q0, scene.v0, r), std::runtime_error);
        continue;
      }
      try {
        integrate(scene.model, scene.settings, scene.q0, scene.v0, r);
        ADD_FAILURE() << "the run went through a loop that cannot close";
      } catch (const SimulationError& e) {
        EXPECT_EQ(e.status, StepStatus::StepTooLarge) << toString(e.status) << ": " << e.what();
        EXPECT_NEAR(e.time, t_star, 1e-5) << e.what();
      }
      continue;
    }
    try {
      integrate(scene.model, scene.settings, scene.q0, scene.v0, r);
      ADD_FAILURE() << "the run went through a loop that cannot close";
    } catch (const SimulationError& e) {
      EXPECT_EQ(e.status, StepStatus::LoopCannotClose) << toString(e.status) << ": " << e.what();
      EXPECT_EQ(e.element, "wrist_pin");
    }
  }
}

TEST_P(EveryIntegrator, EndsAtOnceWithCheckFailedOnAMotionThatIsNotFinite) {
  LoadedScene loaded = loadScene({"motion.yaml", R"(settings: {step: 1.0e-3, end_time: 0.1}
elements:
  - {name: x, type: prismatic, parent: ground, axis: [1, 0, 0], motion: {polynomial: [0, 1, 0]}}
  - {name: y, type: prismatic, parent: x, axis: [0, 1, 0]}
bodies:
  - {name: mass, frame: y, mass: 1, Ixx: 1, Iyy: 1, Izz: 1}
)"});
  Scene& scene = loaded.scene;
  for (const bool by_accuracy : {false, true}) {
    IntegrationRequest r = request();
    if (by_accuracy) r.accuracy = ErrorTolerance{1e-6, 0.0};
    // The drive's acceleration overflows, 2 × 1e308: at t = 0 already, before any step size is chosen.
    Model model = scene.model;
    model.setParameter("x.motion.polynomial.2", 1e308);
    try {
      integrate(model, scene.settings, scene.q0, scene.v0, r);
      ADD_FAILURE() << "a motion that is not finite went through";
    } catch (const SimulationError& e) {
      EXPECT_EQ(e.status, StepStatus::CheckFailed) << toString(e.status) << ": " << e.what();
      EXPECT_EQ(e.element, "x");
    }
  }
}

TEST_P(EveryIntegrator, ItsExactGradientIsThatOfCentralDifferences) {
  std::string scene = test::kOscillator;
  const std::string fixed = "settings: {step: 1.0e-3, end_time: 1}";
  scene.replace(scene.find(fixed), fixed.size(), "settings: {step: 1.0e-2, end_time: 1, integrator: " + GetParam() + "}");
  const std::string design = R"(design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: position, of: max}
  artificial: {initial: 0.5, lower: -2, upper: 2}
  transcription: {measure: ks}
)";
  const DesignProblem problem = loadDesignProblem({"oscillator.yaml", scene + design});
  DesignNlp exact(problem, "adjoint"), differences(problem, "fd_central");
  NlpEvaluation a, d;
  exact.evaluate(exact.start(), true, a);
  differences.evaluate(differences.start(), true, d);
  ASSERT_EQ(a.constraint_jacobian.rows(), d.constraint_jacobian.rows());
  const double scale = a.constraint_jacobian.col(0).cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  // Central differences at δ = 1e-6 of the scaled variable: truncation ~δ², round-off ~ε/δ of the
  // functional, both below 1e-8 of the column here.
  EXPECT_LT((a.constraint_jacobian.col(0) - d.constraint_jacobian.col(0)).cwiseAbs().maxCoeff(), 1e-7 * scale);
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryIntegrator, testing::ValuesIn(integratorNames()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace mbsopt
