// A design problem as the optimizers see it (DESIGN.md §5): min b_{k+1} over the scaled design
// variables and b_{k+1}, subject to every transcribed constraint ≤ 0 and the variables' bounds,
// with the gradients of the named method. One value evaluation is one simulation.
#pragma once

#include <string>
#include <vector>

#include "optimizers/nlp_problem.hpp"
#include "problems/design_problem.hpp"

namespace mbsopt {

class DesignNlp : public NlpProblem {
 public:
  /// `gradient_method`: one of gradientMethodNames(); `fd_step` for the finite differences.
  DesignNlp(DesignProblem problem, std::string gradient_method, double fd_step = 1e-6);

  Eigen::Index variableCount() const override { return optimisationSize(problem_); }
  Eigen::Index inequalityCount() const override { return static_cast<Eigen::Index>(functionals_.size()); }
  Eigen::VectorXd lowerBounds() const override { return scaledBounds(&DesignVariable::lower, &ArtificialVariable::lower); }
  Eigen::VectorXd upperBounds() const override { return scaledBounds(&DesignVariable::upper, &ArtificialVariable::upper); }
  Eigen::VectorXd start() const override { return initialPoint(problem_); }
  std::string constraintName(Eigen::Index i) const override { return functionals_[static_cast<std::size_t>(i)].name; }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override;

  const DesignProblem& problem() const { return problem_; }
  /// Wall time spent in evaluate() so far: simulations and gradients [s].
  double evaluationSeconds() const { return evaluation_seconds_; }
  const std::vector<ConstraintFunctional>& functionals() const { return functionals_; }

 private:
  /// One bound of every variable, in the scaled units the optimizers see.
  Eigen::VectorXd scaledBounds(double DesignVariable::*variable_bound, double ArtificialVariable::*artificial_bound) const;

  DesignProblem problem_;
  std::vector<ConstraintFunctional> functionals_;
  std::string gradient_method_;
  double fd_step_;
  double evaluation_seconds_ = 0.0;
};

}  // namespace mbsopt
