#include "sensitivity/design_nlp.hpp"

#include "sensitivity/design_evaluation.hpp"
#include "sensitivity/gradient_method.hpp"

namespace mbsopt {

DesignNlp::DesignNlp(DesignProblem problem, std::string gradient_method, double fd_step)
    : problem_(std::move(problem)),
      functionals_(transcribe(problem_)),
      gradient_method_(std::move(gradient_method)),
      fd_step_(fd_step) {
  requireGradientMethod(gradient_method_);
}

Eigen::VectorXd DesignNlp::lowerBounds() const {
  Eigen::VectorXd lower(variableCount());
  for (std::size_t i = 0; i < problem_.design.variables.size(); ++i)
    lower[static_cast<Eigen::Index>(i)] = problem_.design.variables[i].lower / problem_.design.variables[i].scale;
  lower[lower.size() - 1] = problem_.design.artificial.lower / problem_.design.artificial.scale;
  return lower;
}

Eigen::VectorXd DesignNlp::upperBounds() const {
  Eigen::VectorXd upper(variableCount());
  for (std::size_t i = 0; i < problem_.design.variables.size(); ++i)
    upper[static_cast<Eigen::Index>(i)] = problem_.design.variables[i].upper / problem_.design.variables[i].scale;
  upper[upper.size() - 1] = problem_.design.artificial.upper / problem_.design.artificial.scale;
  return upper;
}

void DesignNlp::evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) {
  const DesignResponse response = evaluateDesign(problem_, functionals_, x);
  out.cost = response.cost;
  out.constraints = response.constraints;
  if (!gradients) return;
  const DesignGradient g = designGradient(gradient_method_, problem_, functionals_, x, fd_step_);
  out.cost_gradient = g.cost;
  out.constraint_jacobian = g.constraints;
}

}  // namespace mbsopt
