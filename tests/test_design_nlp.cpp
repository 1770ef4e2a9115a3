// A design problem as the optimizers see it (problems/design_nlp.hpp): scaled bounds and start,
// the same values whether or not gradients are asked for, and the gradients of a point whose values
// were asked for first computed on that point's simulation (kept), equal to the last bit to those
// of a fresh evaluation (the simulation is deterministic).
#include <gtest/gtest.h>

#include "problems/scene_file.hpp"
#include "problems/design_nlp.hpp"
#include "sensitivity/gradient_method.hpp"
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
