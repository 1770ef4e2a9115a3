// Design problems: the tramway's from its file equals the C++ one, the transcription follows the
// paper's (15)-(19), and on an undamped oscillator the constraint functionals (the paper's, an
// integral, a final value) and their gradients match their closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mbsopt/sensitivity/continuous_adjoint.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/optimizers/optimizer.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/design_nlp.hpp"
#include "mbsopt/design/tramway.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

constexpr double kPi = std::numbers::pi;

/// The oscillator with spring.k (scale 10) as its variable and max x as its cost, through b_{k+1}
/// from `b0`, followed by `rest` of its design section (constraints, transcription).
DesignProblem oscillatorProblem(const std::string& b0, const std::string& rest,
                                const std::vector<ParameterOverride>& overrides = {}) {
  const std::string design = "design:\n  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]\n"
                             "  cost: {sensor: position, of: max}\n  artificial: {initial: " + b0 +
                             ", lower: -2, upper: 2}\n" + rest;
  return loadDesignProblem({"o.yaml", std::string(test::kOscillator) + design}, overrides);
}


TEST(DesignProblem, TramwayFileEqualsTheCppProblem) {
  const DesignProblem file =
      loadDesignProblem(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/tramway.yaml"));
  const DesignProblem cpp = tramwayDesignProblem();
  ASSERT_EQ(file.design.variables.size(), cpp.design.variables.size());
  for (std::size_t i = 0; i < cpp.design.variables.size(); ++i) {
    EXPECT_EQ(file.design.variables[i].parameter, cpp.design.variables[i].parameter);
    EXPECT_EQ(file.design.variables[i].lower, cpp.design.variables[i].lower);
    EXPECT_EQ(file.design.variables[i].upper, cpp.design.variables[i].upper);
    EXPECT_EQ(file.design.variables[i].scale, cpp.design.variables[i].scale);
  }
  EXPECT_EQ(initialPoint(file), initialPoint(cpp));
  // the spec's b0 in the optimizers' units (100 kN·m/rad, 10 kN·m·s/rad), and b5
  EXPECT_EQ(initialPoint(cpp), (Eigen::VectorXd(5) << 2.46, 2.46, 1.5, 1.5, 3).finished());
  ASSERT_EQ(file.design.constraints.size(), 2u);
  EXPECT_EQ(file.design.constraints[1].bound, cpp.design.constraints[1].bound);
  // The paper's formulation, named by both; a design that names none takes the grid maximum.
  EXPECT_EQ(file.design.transcription.measure, TimeMeasure::PositivePart);
  EXPECT_EQ(cpp.design.transcription.measure, TimeMeasure::PositivePart);
  EXPECT_EQ(oscillatorProblem("0.5", "").design.transcription.measure, TimeMeasure::GridMax);
  EXPECT_EQ(DesignDescription{}.transcription.measure, TimeMeasure::GridMax);
  // (17)-(19) and (15)-(16): ±a_lat − b5, then ±yaw − 10° for each yaw: six constraints.
  const std::vector<ConstraintFunctional> functionals = transcribe(cpp);
  ASSERT_EQ(functionals.size(), 6u);
  EXPECT_TRUE(functionals[0].artificial == ArtificialUse::InSamples && functionals[1].artificial == ArtificialUse::InSamples);
  EXPECT_EQ(functionals[1].sign, -1.0);
  EXPECT_EQ(functionals[2].artificial, ArtificialUse::None);
  EXPECT_EQ(functionals[5].name, "yaw_rear_below");
  EXPECT_NO_THROW(validate(cpp));
}

// A design variable is its parameter's place in the model, resolved once: the file's and the C++
// problem's are the model's own indices, an unknown name is refused where the variable is made, and
// a variable whose index names another parameter is refused by the transcription (every path to a
// simulation transcribes first), not applied to the wrong number.
TEST(DesignProblem, DesignVariablesAreResolvedOnceToTheModelsParameters) {
  const DesignProblem problem = tramwayDesignProblem();
  const Model& model = problem.scene.model;
  for (const DesignVariable& v : problem.design.variables)
    EXPECT_EQ(v.index, model.parameterIndex(v.parameter)) << v.parameter;
  const DesignProblem file = oscillatorProblem("0.5", "");
  EXPECT_EQ(file.design.variables.at(0).index, file.scene.model.parameterIndex("spring.k"));
  EXPECT_THROW(designVariable(model, "front_secondary.kk", 1.0, 2.0, 1.0), std::invalid_argument);

  DesignProblem swapped = problem;
  std::swap(swapped.design.variables[0].index, swapped.design.variables[2].index);  // k's name, c's place
  try {
    transcribe(swapped);
    ADD_FAILURE() << "a variable whose index names another parameter was transcribed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'front_secondary.k' is not resolved"), std::string::npos) << e.what();
  }
  // applyDesign writes each value at the variable's index, scaled: x · scale, the others untouched.
  Model applied = model;
  Eigen::VectorXd x = initialPoint(problem);
  x[1] = 7.5;
  applyDesign(problem, x, applied);
  EXPECT_EQ(applied.parameter("rear_secondary.k"), 7.5 * problem.design.variables[1].scale);
  EXPECT_EQ(applied.parameter("front_secondary.k"), model.parameter("front_secondary.k"));
}

// x'' + ω² x = 0, x(0) = 1, ω = √k = 2π, over T = 1 s (one period); constraint Ψ = ∫⟨x − b⟩dt.
// With F(Θ) = ∫₀^Θ ⟨cos θ − b⟩dθ: Ψ = F(ωT)/ω, F(2π) = 2(sin θ* − b θ*), θ* = arccos b, and
// dΨ/dω = −F(ωT)/ω² + ⟨cos ωT − b⟩ T/ω, dω/dk = 1/(2ω); dΨ/db = −(time with x > b) = −2θ*/ω.
// Newmark's period error (ωh)²/12 and the trapezoidal rule's O(h²) put the discrete value within
// about 1e-4 relative of Ψ at h = 1 ms. Its derivative converges only at first order: where φ has
// a kink at t* (slope jump G), the trapezoidal error in that cell is G h² s(1 − s)/2 with s the
// kink's place in the cell, whose derivative in t* reaches G h/2. So the discrete dΨ/dk may differ
// from the closed form by Σ (h/2) G_i |dt*_i/dk| (two kinks, θ* and 2π − θ*, t*_i = θ_i/ω), plus
// O(h²) and the O(δ²) ≈ 1e-8 of central differences.
TEST(DesignProblem, OscillatorConstraintAndGradientMatchClosedForms) {
  const SceneSource source{"oscillator.yaml", std::string(test::kOscillator) + test::kOscillatorDesign};
  const DesignProblem problem = loadDesignProblem(source);
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  ASSERT_EQ(functionals.size(), 1u);
  const Eigen::VectorXd x = initialPoint(problem);
  const double omega = 2.0 * kPi, b = 0.5, theta = std::acos(b);
  const double F = 2.0 * (std::sin(theta) - b * theta);
  const double psi = F / omega;
  const double dpsi_domega = -F / (omega * omega) + (1.0 - b) / omega;
  const double dpsi_dx = dpsi_domega / (2.0 * omega) * 10.0;  // x = k / 10

  const DesignResponse response = evaluateDesign(problem, functionals, x);
  EXPECT_NEAR(response.constraints[0], psi, 1e-4 * psi);
  const DesignGradient central = finiteDifferenceGradient(problem, functionals, x, 1e-4, true);
  const double h = 1e-3, slope = omega * std::sin(theta), dt_dk = 1.0 / (omega * omega) / (2.0 * omega);
  const double kink_bound = 0.5 * h * slope * (theta + (2.0 * kPi - theta)) * dt_dk * 10.0;  // in x = k / 10
  EXPECT_NEAR(central.constraints(0, 0), dpsi_dx, kink_bound + 1e-4 * std::abs(dpsi_dx));
  EXPECT_NEAR(central.constraints(0, 1), -2.0 * theta / omega, 2e-3);  // the exceedance time, to ±h
  EXPECT_EQ(central.cost, Eigen::Vector2d(0.0, 1.0));                  // the cost is b itself
  // Forward differences carry an O(δ) error, central ones O(δ²): the forward gap is the larger.
  const DesignGradient forward = finiteDifferenceGradient(problem, functionals, x, 1e-4, false);
  EXPECT_GT(std::abs(forward.constraints(0, 0) - dpsi_dx), std::abs(central.constraints(0, 0) - dpsi_dx));
  EXPECT_NEAR(forward.constraints(0, 0), dpsi_dx, kink_bound + 1e-2 * std::abs(dpsi_dx));
}

// ∫₀^τ x dt ≤ 0.1 and x(τ) ≤ 0.5 for x = cos(ωt), ω = √k = 2π, τ = 0.8 s: ∫x dt = sin(ωτ)/ω and
// x(τ) = cos(ωτ), and their k-derivatives through dω/dk = 1/(2ω). Every gradient method matches
// these; the error is the trapezoidal Newmark's phase error (ω_h = ω(1 − ω²h²/12 + …)), a relative
// ω²h²/12 · ωτ = 1.7e-5 here, so 2e-4 of the largest term bounds it with a tenfold margin. The
// continuous adjoint takes the final value's point source as a density over the last half step, so
// its derivative is that of x at a time up to h earlier: within h |d²x/dτdk|.
TEST(DesignProblem, OscillatorIntegralAndFinalValueMatchClosedFormsByEveryMethod) {
  const DesignProblem problem = oscillatorProblem("2", R"(  constraints:
    - {sensor: position, of: integral, bound: 0.1}
    - {sensor: position, of: final, bound: 0.5}
)",
                                                   {{"settings.end_time", 0.8}});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  ASSERT_EQ(functionals.size(), 3u);  // the cost's, the integral, the final value
  EXPECT_EQ(functionals[1].name, "position_integral");
  EXPECT_EQ(functionals[2].name, "position_final");
  const double omega = 2.0 * kPi, tau = 0.8, dk_dx = 10.0, domega_dk = 1.0 / (2.0 * omega);
  const Eigen::Vector2d value(std::sin(omega * tau) / omega - 0.1, std::cos(omega * tau) - 0.5);
  const Eigen::Vector2d dvalue_dx =
      Eigen::Vector2d(tau * std::cos(omega * tau) / omega - std::sin(omega * tau) / (omega * omega),
                      -tau * std::sin(omega * tau)) * domega_dk * dk_dx;
  const double h = 1e-3, ddvalue_dtaudx = -(std::sin(omega * tau) + omega * tau * std::cos(omega * tau)) * domega_dk * dk_dx;
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse response = evaluateDesign(problem, functionals, x);
  const double tolerance = 2e-4 * std::max(value.cwiseAbs().maxCoeff(), dvalue_dx.cwiseAbs().maxCoeff());
  EXPECT_NEAR(response.constraints[1], value[0], tolerance);
  EXPECT_NEAR(response.constraints[2], value[1], tolerance);
  for (const auto& [name, gradient] :
       {std::pair{"adjoint", adjointGradient(problem, functionals, x)},
        std::pair{"continuous-adjoint", continuousAdjointGradient(problem, functionals, x)},
        std::pair{"direct", directGradient(problem, functionals, x)},
        std::pair{"fd_central", finiteDifferenceGradient(problem, functionals, x, 1e-5, true)}}) {
    EXPECT_NEAR(gradient.constraints(1, 0), dvalue_dx[0], tolerance) << name;
    const double shift = name == std::string("continuous-adjoint") ? h * std::abs(ddvalue_dtaudx) : 0.0;
    EXPECT_NEAR(gradient.constraints(2, 0), dvalue_dx[1], tolerance + shift) << name;
    EXPECT_EQ(gradient.constraints(1, 1), 0.0) << name;  // b_{k+1} is the cost's alone
  }
}

// An RMS cost, √((1/τ)∫x²dt), through b_{k+1} after the measure: the constraint RMS − b ≤ 0, whose
// artificial column is −1. For x = cos ωt, RMS² = 1/2 + sin(2ωτ)/(4ωτ), and its k-derivative
// through dω/dk = 1/(2ω); the phase error of the trapezoidal Newmark (a relative ω²h²/12 · ωτ =
// 1.7e-5) bounds the difference, with 2e-4 of the largest term as in the integral's test. An RMS
// constraint with a bound is RMS − bound.
TEST(DesignProblem, AnRmsCostAndAnRmsConstraintMatchTheirClosedFormsByEveryMethod) {
  const std::string design = R"(design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: position, of: rms}
  artificial: {initial: 0.5, lower: 0, upper: 2}
  constraints: [{sensor: position, of: rms, bound: 0.6}]
)";
  const DesignProblem problem =
      loadDesignProblem({"o.yaml", std::string(test::kOscillator) + design}, {{"settings.end_time", 0.8}});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  ASSERT_EQ(functionals.size(), 2u);
  EXPECT_EQ(functionals[0].name, "position_rms");
  EXPECT_EQ(functionals[0].artificial, ArtificialUse::AfterMeasure);
  EXPECT_EQ(functionals[1].name, "position_rms_2");
  EXPECT_EQ(functionals[1].artificial, ArtificialUse::None);
  const double omega = 2.0 * kPi, tau = 0.8, dk_dx = 10.0, domega_dk = 1.0 / (2.0 * omega);
  const double square = 0.5 + std::sin(2.0 * omega * tau) / (4.0 * omega * tau);
  const double rms = std::sqrt(square);
  const double dsquare_domega = std::cos(2.0 * omega * tau) / (2.0 * omega) - std::sin(2.0 * omega * tau) / (4.0 * omega * omega * tau);
  const double drms_dx = dsquare_domega / (2.0 * rms) * domega_dk * dk_dx;
  const double tolerance = 2e-4 * std::max(rms, std::abs(drms_dx));
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse response = evaluateDesign(problem, functionals, x);
  EXPECT_NEAR(response.constraints[0], rms - 0.5, tolerance);
  EXPECT_NEAR(response.constraints[1], rms - 0.6, tolerance);
  for (const auto& [name, gradient] :
       {std::pair{"adjoint", adjointGradient(problem, functionals, x)},
        std::pair{"continuous-adjoint", continuousAdjointGradient(problem, functionals, x)},
        std::pair{"direct", directGradient(problem, functionals, x)},
        std::pair{"fd_central", finiteDifferenceGradient(problem, functionals, x, 1e-5, true)}}) {
    EXPECT_NEAR(gradient.constraints(0, 0), drms_dx, tolerance) << name;
    EXPECT_NEAR(gradient.constraints(1, 0), drms_dx, tolerance) << name;
    EXPECT_EQ(gradient.constraints(0, 1), -1.0) << name;  // RMS − b
    EXPECT_EQ(gradient.constraints(1, 1), 0.0) << name;
  }
}

// An integral cost: b_{k+1} = ∫x dt at the optimum, the constraint ∫x dt − b ≤ 0 (for x = cos ωt,
// ∫₀^τ x dt = sin(ωτ)/ω).
TEST(DesignProblem, AnIntegralCostIsItsEpigraph) {
  const std::string design = R"(design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: position, of: integral}
  artificial: {initial: 0.5, lower: -2, upper: 2}
)";
  const DesignProblem problem =
      loadDesignProblem({"o.yaml", std::string(test::kOscillator) + design}, {{"settings.end_time", 0.8}});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  ASSERT_EQ(functionals.size(), 1u);
  EXPECT_EQ(functionals[0].name, "position_integral");
  const double omega = 2.0 * kPi, tau = 0.8;
  const DesignResponse response = evaluateDesign(problem, functionals, initialPoint(problem));
  EXPECT_NEAR(response.constraints[0], std::sin(omega * tau) / omega - 0.5, 2e-4 * 0.5);
  EXPECT_EQ(adjointGradient(problem, functionals, initialPoint(problem)).constraints(0, 1), -1.0);
}

TEST(DesignProblem, BadDesignSectionsAreLocated) {
  const std::string scene = std::string(test::kOscillator) + "design:\n";
  const auto errorLine = [&](const std::string& design) {
    try {
      loadDesignProblem({"d.yaml", scene + design});
    } catch (const SceneError& e) {
      return e.line();
    }
    return -1;
  };
  const std::string cost = "  cost: {sensor: position}\n  artificial: {initial: 0, lower: -2, upper: 2}\n";
  EXPECT_EQ(errorLine("  variables: [{parameter: spring.kk, lower: 1, upper: 100}]\n" + cost), 11);
  EXPECT_EQ(errorLine("  variables: [{parameter: spring.k, lower: 50, upper: 100}]\n" + cost), 11);  // k = 39.5 ∉ [50, 100]
  EXPECT_EQ(errorLine("  variables: [{parameter: spring.k, lower: 1, upper: 100}]\n  cost: {sensor: speed}\n"
                      "  artificial: {initial: 0, lower: -2, upper: 2}\n"),
            12);
  EXPECT_EQ(errorLine("  variables: [{parameter: spring.k, lower: 1, upper: 100}]\n  cost: {sensor: position, of: final}\n"
                      "  artificial: {initial: 0, lower: -2, upper: 2}\n"),
            12);  // a cost is an extreme over time
  EXPECT_THROW(loadDesignProblem({"d.yaml", scene.substr(0, scene.rfind("design:"))}), SceneError);  // none
  const std::string start = "  variables: [{parameter: spring.k, lower: 1, upper: 100}]\n" + cost + "  constraints:\n";
  EXPECT_EQ(errorLine(start + "    - {sensor: position, of: final, bound: 0, equals: 0}\n"), 15);  // both
  EXPECT_EQ(errorLine(start + "    - {sensor: position, of: max, equals: 0}\n"), 15);  // an extreme is no equality
  EXPECT_EQ(errorLine(start + "    - {sensor: position, of: final}\n"), 15);            // neither
}

// `of: min` keeps min_t y ≥ bound as −y + bound ≤ 0, transcribed like the maxima; `equals:` makes an
// integral or a final value an equality, which the optimizers see after every inequality
// (NlpProblem's order), whatever the file's order.
TEST(DesignProblem, MinimaAreTranscribedAndEqualitiesComeLast) {
  const DesignProblem problem = oscillatorProblem("1.5", R"(  constraints:
    - {sensor: position, of: final, equals: 0.25}
    - {sensor: position, of: min, bound: -0.5}
    - {sensor: position, of: integral, bound: 0.1}
)");
  ASSERT_EQ(problem.design.constraints.size(), 3u);
  EXPECT_TRUE(problem.design.constraints[0].equality);
  EXPECT_EQ(problem.design.constraints[0].bound, 0.25);
  EXPECT_EQ(problem.design.constraints[1].of, ResponseMeasure::Min);
  const std::vector<ConstraintFunctional> f = transcribe(problem);
  ASSERT_EQ(f.size(), 4u);  // the cost's, the minimum's, the integral's, then the equality
  EXPECT_EQ(f[1].name, "position_min");
  EXPECT_EQ(f[1].sign, -1.0);
  EXPECT_EQ(f[1].offset, -(-0.5));
  EXPECT_FALSE(f[1].equality);
  EXPECT_EQ(f[2].name, "position_integral");
  EXPECT_EQ(f[3].name, "position_final");
  EXPECT_TRUE(f[3].equality);
  EXPECT_EQ(f[3].offset, 0.25);
  // Several constraints on one sensor: the cost's maximum and two more bounds on it, each named apart.
  const DesignProblem repeated = oscillatorProblem("1.5", R"(  constraints:
    - {sensor: position, of: max, bound: 1.2}
    - {sensor: position, of: max_abs, bound: 1.5}
)");
  std::vector<std::string> names;
  for (const ConstraintFunctional& g : transcribe(repeated)) names.push_back(g.name);
  EXPECT_EQ(names, (std::vector<std::string>{"position_above", "position_above_2", "position_above_3", "position_below"}));
  // x(t) = cos(2πt) at k = (2π)²: min x = −1 < −0.5 violates the minimum by 0.5 (φ = −x − 0.5 at
  // its largest), and x(1) − 0.25 = 0.75, to Newmark's period error (about 1e-4).
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse response = evaluateDesign(problem, f, x);
  EXPECT_NEAR(response.functionals[3].value, 0.75, 1e-3);
}

// `windows: W` splits the run's time points into W equal windows (windowPoints: every point in exactly
// one, each of at least two) and measures each extreme on each window as a constraint of its own,
// named _w1 … _wW. On x = cos(2πt) over one period with four windows the grid maxima of x are those
// of its quarters, read from the trajectory by their times; each window's gradient vanishes outside it.
TEST(DesignProblem, TranscriptionWindowsMeasureEachExtremeOnEachWindow) {
  for (const Eigen::Index points : {5, 6, 1001})
    for (int windows = 1; 2 * windows <= points; ++windows) {
      Eigen::Index next = 0;
      for (int w = 0; w < windows; ++w) {
        const auto [first, count] = windowPoints(w, windows, points);
        EXPECT_EQ(first, next);
        EXPECT_GE(count, 2);
        next = first + count;
      }
      EXPECT_EQ(next, points);
    }
  EXPECT_THROW(windowPoints(1, 3, 5), std::invalid_argument);  // the points 0-1, 2, 3-4
  const DesignProblem problem = oscillatorProblem("1.5", R"(  constraints:
    - {sensor: position, of: max_abs, bound: 1.5}
  transcription: {measure: grid_max, windows: 4}
)");
  const std::vector<ConstraintFunctional> f = transcribe(problem);
  std::vector<std::string> names;
  for (const ConstraintFunctional& g : f) names.push_back(g.name);
  EXPECT_EQ(names, (std::vector<std::string>{"position_above_w1", "position_above_w2", "position_above_w3",
                                             "position_above_w4", "position_above_w1_2", "position_below_w1",
                                             "position_above_w2_2", "position_below_w2", "position_above_w3_2",
                                             "position_below_w3", "position_above_w4_2", "position_below_w4"}));
  const DesignResponse response = evaluateDesign(problem, f, initialPoint(problem));
  const Eigen::VectorXd& t = response.trajectory.time;
  const Eigen::VectorXd x = response.trajectory.sensors.col(0);
  for (int w = 0; w < 4; ++w) {
    // The quarter [w/4, (w + 1)/4), the last one closed, by the times themselves.
    double largest = -1e300;
    for (Eigen::Index k = 0; k < t.size(); ++k)
      if (t[k] >= 0.25 * w - 1e-12 && (t[k] < 0.25 * (w + 1) - 1e-12 || w == 3)) largest = std::max(largest, x[k]);
    const std::size_t cost = static_cast<std::size_t>(w), bound = 4 + 2 * static_cast<std::size_t>(w);
    EXPECT_EQ(response.functionals[cost].value, largest - 1.5) << w;  // x − b, b = 1.5
    EXPECT_EQ(response.functionals[bound].value, largest - 1.5) << w;
    const auto [first, count] = windowPoints(w, 4, t.size());
    const Eigen::VectorXd& gradient = response.functionals[cost].gradient;
    EXPECT_EQ(gradient.segment(first, count).sum(), 1.0);
    EXPECT_EQ(gradient.cwiseAbs().sum(), 1.0) << "a gradient outside its window";
  }
  try {
    oscillatorProblem("1.5", "  transcription: {measure: grid_max, windows: 501}\n");
    FAIL() << "501 windows of 1001 points were accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 14) << e.what();  // the transcription's
  }
}

/// The oscillator with its acceleration sensor, a design on k, and two load cases that release it
/// from 1 m and from 0.5 m.
std::string twoCaseOscillator(const std::string& cases) {
  return std::string(test::kOscillator) + R"(  - {name: acceleration, type: joint, joint: x, quantity: acceleration}
design:
  variables: [{parameter: spring.k, lower: 1, upper: 100, scale: 10}]
  cost: {sensor: acceleration, of: max_abs}
  artificial: {initial: 50, lower: 0, upper: 200}
  constraints:
    - {sensor: position, of: final, bound: 0.9}
    - {sensor: position, of: integral, equals: 0}
  transcription: {measure: grid_max}
  load_cases:
)" + cases;
}

// Load cases: each case's scene is the file with the case's numbers set, simulated on its own; its
// constraints are named after it, every inequality before every equality; the cost's epigraph takes
// b_{k+1} in every case, so the cost is the worst case's. The values and the exact gradients of each
// case are those of the scene loaded with the same numbers by --set (an independent path), to the
// bit; central differences of the whole problem agree with them.
TEST(DesignProblem, LoadCasesAreSimulatedOneByOneAndShareTheDesign) {
  const DesignProblem problem = loadDesignProblem(
      {"cases.yaml", twoCaseOscillator("    - {name: far, set: {x.q0: 1.0}}\n    - {name: near, set: {x.q0: 0.5}}\n")});
  ASSERT_EQ(problem.load_cases.size(), 2u);
  const std::vector<ConstraintFunctional> f = transcribe(problem);
  std::vector<std::string> names;
  for (const ConstraintFunctional& g : f) names.push_back(g.name);
  EXPECT_EQ(names, (std::vector<std::string>{"acceleration_above_far", "acceleration_below_far", "position_final_far",
                                             "acceleration_above_near", "acceleration_below_near",
                                             "position_final_near", "position_integral_far",
                                             "position_integral_near"}));
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse response = evaluateDesign(problem, f, x);
  const DesignGradient adjoint = designGradient("adjoint", problem, f, x, 1e-6, &response);
  const DesignGradient direct = designGradient("direct", problem, f, x, 1e-6, &response);
  std::vector<Eigen::Index> rows;
  for (const auto& [c, q0] : {std::pair<int, double>{0, 1.0}, {1, 0.5}}) {
    const DesignProblem alone = loadDesignProblem({"cases.yaml", twoCaseOscillator("")}, {{"x.q0", q0}});
    const std::vector<ConstraintFunctional> own = loadCaseFunctionals(f, c, &rows);
    const DesignResponse single = evaluateDesign(alone, transcribe(alone), x);
    const DesignGradient single_adjoint = adjointGradient(alone, transcribe(alone), x);
    ASSERT_EQ(rows.size(), 4u);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(response.constraints[rows[i]], single.constraints[static_cast<Eigen::Index>(i)]) << names[rows[i]];
      EXPECT_EQ(adjoint.constraints.row(rows[i]), single_adjoint.constraints.row(static_cast<Eigen::Index>(i))) << names[rows[i]];
    }
    EXPECT_EQ(caseTrajectory(response, static_cast<std::size_t>(c)).q(0, 0), q0);
    EXPECT_EQ(loadCaseResponse(response, static_cast<std::size_t>(c)).constraints, single.constraints);
  }
  EXPECT_EQ(response.made_of, ResponseParts::LoadCases);
  EXPECT_EQ(response.trajectory.time.size(), 0);  // each case's is its own
  EXPECT_THROW(extrapolationRunResponse(response, 1), std::logic_error);
  EXPECT_LE((adjoint.constraints - direct.constraints).cwiseAbs().maxCoeff(), 1e-12 * adjoint.constraints.cwiseAbs().maxCoeff());
  const DesignGradient central = finiteDifferenceGradient(problem, f, x, 1e-5, true);
  EXPECT_LE((central.constraints - adjoint.constraints).cwiseAbs().maxCoeff(), 1e-6 * adjoint.constraints.cwiseAbs().maxCoeff());
  // The cost's epigraph in every case: max a − b, the peak k x₀ = 39.5 from 1 m, 19.7 from 0.5 m, to
  // the Newmark period error's few 1e-4.
  EXPECT_NEAR(response.constraints[0], 39.478 - 50.0, 0.03);
  EXPECT_NEAR(response.constraints[3], 0.5 * 39.478 - 50.0, 0.03);
}

TEST(DesignProblem, BadLoadCasesAreLocated) {
  const auto errorLine = [&](const std::string& cases) {
    try {
      loadDesignProblem({"cases.yaml", twoCaseOscillator(cases)});
    } catch (const SceneError& e) {
      return e.line();
    }
    return -1;
  };
  // Line 20 is the first case.
  EXPECT_EQ(errorLine("    - {name: far, set: {x.q1: 1.0}}\n"), 20);                       // no such number
  EXPECT_EQ(errorLine("    - {name: far, set: {design.artificial.initial: 1}}\n"), 20);    // not the scene's
  EXPECT_EQ(errorLine("    - {name: far}\n    - {name: far, set: {x.q0: 2}}\n"), 21);  // a repeated name
  EXPECT_EQ(errorLine("    - {name: far, set: [1, 2]}\n"), 20);                            // not a map
  EXPECT_EQ(errorLine("    - {name: far, set: {spring.k: 5}}\n"), 20);  // a design variable: the design's value
  EXPECT_EQ(errorLine("    - {name: far, set: {x.q0: 2}}\n"), -1);
}

// x'' + k x = 0 from x(0) = 1 (the oscillator) with x(1) = 0 as an equality. Newmark's average
// acceleration turns an undamped oscillation by ω̃h per step with tan(ω̃h/2) = ωh/2 (the trapezoidal
// rule's exact phase), so the grid's x(1) = cos(ω̃) vanishes where ω̃ = (2n + 1)π/2: k =
// ((2/h) tan(ω̃h/2))², exactly. The optimizers that take equalities stop on one of those roots within
// their feasibility tolerance (1e-6 on x(1), so 1e-6/ω̃ on ω̃, below 1e-6 relative on k); MMA and
// CCSAQ say they cannot take the problem.
TEST(DesignProblem, AnEqualityOnAFinalValueIsMetOnTheGridsRoot) {
  const DesignProblem problem = oscillatorProblem("1.5", R"(  constraints:
    - {sensor: position, of: final, equals: 0}
  transcription: {measure: grid_max}
)");
  const double h = problem.scene.settings.step;
  std::vector<double> roots;
  for (int n = 0; n < 4; ++n) roots.push_back(std::pow(2.0 / h * std::tan((2 * n + 1) * kPi / 2 * h / 2), 2));
  for (const std::string optimizer : {"sdcc", "slsqp", "ipopt"}) {
    DesignNlp nlp(problem, "adjoint");
    EXPECT_EQ(nlp.equalityCount(), 1);
    EXPECT_EQ(nlp.inequalityCount(), 1);
    const OptimizerResult r = minimize(optimizer, nlp, OptimizerOptions{});
    EXPECT_EQ(r.status, OptimizerStatus::Converged) << optimizer << ": " << r.message;
    const double k = r.x[0] * problem.design.variables[0].scale;
    double nearest = 1e300;
    for (const double root : roots) nearest = std::min(nearest, std::abs(k - root) / root);
    EXPECT_LE(nearest, 1e-6) << optimizer << ": k = " << k;
  }
  for (const std::string optimizer : {"mma", "ccsaq"}) {
    DesignNlp nlp(problem, "adjoint");
    EXPECT_EQ(minimize(optimizer, nlp, OptimizerOptions{}).status, OptimizerStatus::Unsupported) << optimizer;
  }
}

}  // namespace
}  // namespace mbsopt
