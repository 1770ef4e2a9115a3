#include "sensitivity/design_nlp.hpp"

#include <chrono>

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

Eigen::VectorXd DesignNlp::scaledBounds(double DesignVariable::*variable_bound,
                                        double ArtificialVariable::*artificial_bound) const {
  const DesignDescription& d = problem_.design;
  Eigen::VectorXd bounds(variableCount());
  for (std::size_t i = 0; i < d.variables.size(); ++i)
    bounds[static_cast<Eigen::Index>(i)] = d.variables[i].*variable_bound / d.variables[i].scale;
  bounds[bounds.size() - 1] = d.artificial.*artificial_bound / d.artificial.scale;
  return bounds;
}

void DesignNlp::evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) {
  const auto start_time = std::chrono::steady_clock::now();
  std::optional<DesignValues> values;
  if (gradients) {
    DesignGradient g = designGradient(gradient_method_, problem_, functionals_, x, fd_step_);
    out.cost_gradient = std::move(g.cost);
    out.constraint_jacobian = std::move(g.constraints);
    values = std::move(g.values);  // the exact methods' own simulation: no second one
  }
  if (!values) {
    const DesignResponse response = evaluateDesign(problem_, functionals_, x);
    values = DesignValues{response.cost, response.constraints};
  }
  out.cost = values->cost;
  out.constraints = std::move(values->constraints);
  evaluation_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
}

}  // namespace mbsopt
