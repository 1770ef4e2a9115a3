// Scenes and closed forms shared by the integrator tests (test_extrapolation, test_adaptive_newmark).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt::test {

inline constexpr double kOmega = 2.0 * std::numbers::pi;  // the oscillator's ω: k = (2π)² N/m, m = 1 kg

/// x'' = −ω²x from x₀ = 1 at rest (exact solution cos ωt) over `end_time`.
inline Scene oscillator(double end_time) {
  LoadedScene loaded = loadScene({"oscillator.yaml", kOscillator});
  loaded.scene.settings.end_time = end_time;
  return std::move(loaded.scene);
}

/// A scene file of the repository, by its path from the source directory.
inline Scene sceneFile(const std::string& relative) {
  const std::string path = std::string(MBSOPT_SOURCE_DIR) + "/" + relative;
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return loadScene({path, text.str()}).scene;
}

/// max over the time points of |x − cos ωt|: the true global error of a run's coordinate 0.
inline double trueOscillatorError(const Trajectory& t) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < t.time.size(); ++k) worst = std::max(worst, std::abs(t.q(0, k) - std::cos(kOmega * t.time[k])));
  return worst;
}

/// Andrews' squeezer's angles β, Θ, γ, Φ, δ, Ω, ε at t = 0.03 s as the test set publishes them
/// (problems/scenes/hard/reference/andrews_squeezer.csv); the scene's sensors in that order.
inline const std::vector<double> kAndrewsPublished{15.810771196299040,   -15.756371059842980, 0.040822240130731012,
                                                    -0.53473011632269485, 0.52440996588053035, 0.53473011632269485,
                                                    1.0480807410422630};

/// Andrews' squeezer (stiff spring, three loops meeting at one point) run by `integrator` to each
/// accuracy against the test set's values at t = 0.03 s: the error of the angles relative to 1 + |y|
/// below twice the tolerance, and within 10 times of the run's own estimate either way.
inline void expectAndrewsMeetsThePublishedAngles(const std::string& integrator, const std::vector<double>& tolerances) {
  const Scene scene = sceneFile("problems/scenes/hard/andrews_squeezer.yaml");
  const std::vector<double>& published = kAndrewsPublished;
  for (const double tolerance : tolerances) {
    IntegrationRequest request;
    request.accuracy = ErrorTolerance{tolerance, 0.0};
    request.integrator.name = integrator;
    request.output_step = 0.03;
    const Integration integration = integrate(scene.model, scene.settings, scene.q0, scene.v0, request);
    const Trajectory& t = integration.run.trajectory;
    ASSERT_EQ(t.time.size(), 2);
    double error = 0.0, estimate = 0.0;
    for (Eigen::Index s = 0; s < 7; ++s) {
      const double scale = 1.0 + std::abs(published[static_cast<std::size_t>(s)]);
      error = std::max(error, std::abs(t.sensors(1, s) - published[static_cast<std::size_t>(s)]) / scale);
      estimate = std::max(estimate, std::abs(integration.run.sensor_error(1, s)) / scale);
    }
    EXPECT_LT(error, 2.0 * tolerance) << integrator << " at " << tolerance;
    EXPECT_LT(error, 10.0 * estimate) << integrator << " at " << tolerance;
    EXPECT_LT(estimate, 10.0 * error) << integrator << " at " << tolerance;
  }
}

}  // namespace mbsopt::test
