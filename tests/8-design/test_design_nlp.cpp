// A design problem as the optimizers see it (8-design/design_nlp.hpp): scaled bounds and start,
// the same values whether or not gradients are asked for, and the gradients of a point whose values
// were asked for first computed on that point's simulation (kept), equal to the last bit to those
// of a fresh evaluation (the simulation is deterministic).
#include <gtest/gtest.h>

#include <string>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/design_nlp.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

DesignProblem chain() { return loadDesignProblem({"chain.yaml", test::kOpenChainProblem}); }

TEST(DesignNlp, BoundsAndStartAreInTheScaledVariables) {
  const DesignNlp nlp(chain(), "adjoint");
  const DesignDescription& d = nlp.problem().design;
  ASSERT_EQ(nlp.variableCount(), static_cast<Eigen::Index>(d.variables.size()) + 1);
  for (std::size_t i = 0; i < d.variables.size(); ++i) {
    const auto j = static_cast<Eigen::Index>(i);
    EXPECT_EQ(nlp.lowerBounds()[j], d.variables[i].lower / d.variables[i].scale);
    EXPECT_EQ(nlp.upperBounds()[j], d.variables[i].upper / d.variables[i].scale);
  }
  EXPECT_EQ(nlp.upperBounds()[nlp.variableCount() - 1], d.artificial.upper / d.artificial.scale);
  EXPECT_EQ(nlp.start(), initialPoint(nlp.problem()));
  EXPECT_EQ(nlp.inequalityCount(), static_cast<Eigen::Index>(nlp.functionals().size()));
}

TEST(DesignNlp, ValuesDoNotDependOnWhetherGradientsAreAskedFor) {
  for (const std::string& method : gradientMethodNames()) {
    DesignNlp nlp(chain(), method);
    const Eigen::VectorXd x = nlp.start();
    NlpEvaluation plain, with_gradients;
    nlp.evaluate(x, false, plain);
    nlp.evaluate(x, true, with_gradients);
    EXPECT_EQ(plain.cost, with_gradients.cost) << method;
    EXPECT_EQ(plain.constraints, with_gradients.constraints) << method;
    EXPECT_EQ(with_gradients.constraint_jacobian.rows(), nlp.inequalityCount()) << method;
    EXPECT_EQ(with_gradients.cost_gradient.size(), nlp.variableCount()) << method;
  }
}

TEST(DesignNlp, GradientsAfterValuesReuseThePointsSimulation) {
  for (const char* method : {"adjoint", "direct", "fd_forward"}) {
    DesignNlp fresh(chain(), method), reusing(chain(), method);
    const Eigen::VectorXd x = fresh.start(), y = 1.01 * x;
    NlpEvaluation direct, values, reused;
    fresh.evaluate(x, true, direct);
    reusing.evaluate(x, false, values);
    reusing.evaluate(y, false, values);  // a second point in between: x stays kept
    ASSERT_NE(reusing.keptSimulation(x), nullptr) << method;
    reusing.evaluate(x, true, reused);
    EXPECT_EQ(direct.cost, reused.cost) << method;
    EXPECT_EQ(direct.cost_gradient, reused.cost_gradient) << method;
    EXPECT_EQ(direct.constraint_jacobian, reused.constraint_jacobian) << method;
  }
}

TEST(DesignNlp, KeepsTheFirstPointAndTheMostRecentOnes) {
  DesignNlp nlp(chain(), "adjoint");
  const Eigen::VectorXd start = nlp.start();
  NlpEvaluation out;
  std::vector<Eigen::VectorXd> points;
  for (std::size_t k = 0; k <= DesignNlp::kKeptSimulations + 1; ++k) {
    points.push_back((1.0 + 0.001 * static_cast<double>(k)) * start);
    nlp.evaluate(points.back(), false, out);
  }
  EXPECT_NE(nlp.keptSimulation(points[0]), nullptr);  // the first, for the report's "at the start"
  EXPECT_EQ(nlp.keptSimulation(points[1]), nullptr);  // pushed out by the newer ones
  for (std::size_t k = 2; k < points.size(); ++k) EXPECT_NE(nlp.keptSimulation(points[k]), nullptr) << k;
  EXPECT_GT(nlp.simulationSeconds(), 0.0);
}

// Once kKeptSimulations points are kept, each new simulation is written into the buffers of the one
// it pushed out last (DesignNlp's spare buffers). Every kept simulation must still be the one of its
// own point, the same to the bit as a fresh evaluation of that point: every field of the trajectory
// and the measures. On the four-bar, whose cut joint gives multipliers and projections (the
// unprojected rates differ from the trajectory's), so that no field is trivially equal.
TEST(DesignNlp, ASimulationWrittenIntoAForgottenOnesBuffersIsThatOfItsOwnPoint) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  DesignNlp nlp(loadDesignProblem(source, {{"settings.end_time", 0.5}}), "adjoint");
  const Eigen::VectorXd start = nlp.start();
  NlpEvaluation out;
  std::vector<Eigen::VectorXd> points;
  for (std::size_t k = 0; k < 2 * DesignNlp::kKeptSimulations + 2; ++k) {
    points.push_back((1.0 + 0.01 * static_cast<double>(k)) * start);
    nlp.evaluate(points.back(), false, out);
  }
  for (std::size_t k = points.size() - DesignNlp::kKeptSimulations; k < points.size(); ++k) {
    const DesignResponse* kept = nlp.keptSimulation(points[k]);
    ASSERT_NE(kept, nullptr) << k;
    const DesignResponse fresh = evaluateDesign(nlp.problem(), nlp.functionals(), points[k]);
    const Trajectory &a = kept->trajectory, &b = fresh.trajectory;
    ASSERT_GT(b.lambda.rows(), 0);
    ASSERT_NE(b.v_unprojected, b.v);
    EXPECT_EQ(kept->cost, fresh.cost) << k;
    EXPECT_EQ(kept->constraints, fresh.constraints) << k;
    EXPECT_EQ(a.time, b.time) << k;
    EXPECT_EQ(a.q, b.q) << k;
    EXPECT_EQ(a.v, b.v) << k;
    EXPECT_EQ(a.a, b.a) << k;
    EXPECT_EQ(a.lambda, b.lambda) << k;
    EXPECT_EQ(a.v_unprojected, b.v_unprojected) << k;
    EXPECT_EQ(a.a_unprojected, b.a_unprojected) << k;
    EXPECT_EQ(a.sensors, b.sensors) << k;
    EXPECT_EQ(a.closure_error, b.closure_error) << k;
    EXPECT_EQ(a.newton_iterations, b.newton_iterations) << k;
    EXPECT_EQ(a.statistics.steps, b.statistics.steps) << k;
    EXPECT_EQ(a.statistics.newton_iterations, b.statistics.newton_iterations) << k;
    ASSERT_EQ(kept->functionals.size(), fresh.functionals.size()) << k;
    for (std::size_t j = 0; j < fresh.functionals.size(); ++j) {
      EXPECT_EQ(kept->functionals[j].value, fresh.functionals[j].value) << k;
      EXPECT_EQ(kept->functionals[j].gradient, fresh.functionals[j].gradient) << k;
    }
  }
}

// A point anticipated with two jobs is simulated on another thread while this one evaluates
// another point; its evaluation then uses that simulation, and what it returns is the same to the
// bit as a plain evaluation's (the simulation depends only on the problem and the point).
TEST(DesignNlp, APointSimulatedAheadGivesTheSameValuesAndGradientsToTheBit) {
  DesignNlp ahead(chain(), "adjoint", 1e-6, 2), plain(chain(), "adjoint", 1e-6, 2);
  const Eigen::VectorXd x = ahead.start(), y = 1.01 * x;
  NlpEvaluation at_x, from_ahead, reference;
  ahead.anticipate(y);
  ahead.evaluate(x, false, at_x);  // on this thread, while y's simulation runs on another
  ahead.evaluate(y, true, from_ahead);
  plain.evaluate(y, true, reference);
  EXPECT_EQ(ahead.simulationsAhead(), 1);
  EXPECT_EQ(ahead.simulationsAheadUsed(), 1);
  EXPECT_EQ(from_ahead.cost, reference.cost);
  EXPECT_EQ(from_ahead.constraints, reference.constraints);
  EXPECT_EQ(from_ahead.cost_gradient, reference.cost_gradient);
  EXPECT_EQ(from_ahead.constraint_jacobian, reference.constraint_jacobian);
  EXPECT_EQ(plain.simulationsAhead(), 0);
}

// Nothing runs ahead with one job (no spare core), nor for a point already simulated.
TEST(DesignNlp, AnticipatesNothingWithOneJobOrForAKeptPoint) {
  DesignNlp one_job(chain(), "adjoint"), two_jobs(chain(), "adjoint", 1e-6, 2);
  const Eigen::VectorXd x = one_job.start();
  NlpEvaluation out;
  one_job.anticipate(x);
  one_job.evaluate(x, false, out);
  EXPECT_EQ(one_job.simulationsAhead(), 0);
  two_jobs.evaluate(x, false, out);
  two_jobs.anticipate(x);
  EXPECT_EQ(two_jobs.simulationsAhead(), 0);
}

// A simulation that fails ahead of time fails its evaluation as a plain one would, with the same
// error; one never asked for is dropped silently.
TEST(DesignNlp, ASimulationThatFailsAheadFailsItsEvaluationTheSameWay) {
  DesignNlp ahead(chain(), "adjoint", 1e-6, 2), plain(chain(), "adjoint", 1e-6, 2);
  Eigen::VectorXd broken = ahead.start();
  broken[2] = 0.0;  // a massless lower link: nothing resists the elbow's motion
  std::string plain_error, ahead_error;
  NlpEvaluation out;
  try {
    plain.evaluate(broken, false, out);
  } catch (const std::exception& e) {
    plain_error = e.what();
  }
  ASSERT_FALSE(plain_error.empty());
  ahead.anticipate(broken);
  try {
    ahead.evaluate(broken, false, out);
  } catch (const std::exception& e) {
    ahead_error = e.what();
  }
  EXPECT_EQ(ahead_error, plain_error);
  EXPECT_EQ(ahead.simulationsAheadUsed(), 1);
  DesignNlp unused(chain(), "adjoint", 1e-6, 2);
  unused.anticipate(broken);  // destroyed with its failed simulation never asked for
}

TEST(DesignNlp, AnUnknownGradientMethodIsAnErrorThatListsTheKnownOnes) {
  try {
    DesignNlp nlp(chain(), "complex-step");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("continuous-adjoint"), std::string::npos);
  }
}

}  // namespace
}  // namespace mbsopt
