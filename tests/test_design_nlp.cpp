// A design problem as the optimizers see it (sensitivity/design_nlp.hpp): scaled bounds and start,
// and the same values whether or not gradients are asked for (the exact methods hand back the
// values of their own simulation, finite differences leave them to a separate one; both are the
// same deterministic simulation of the same x, so equal to the last bit).
#include <gtest/gtest.h>

#include "problems/scene_file.hpp"
#include "sensitivity/design_nlp.hpp"
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
