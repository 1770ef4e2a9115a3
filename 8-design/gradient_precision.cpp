#include "mbsopt/design/gradient_precision.hpp"

#include <optional>
#include <stdexcept>

#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/design/gradient_difference.hpp"

namespace mbsopt {

namespace {

/// The problem's time step h, in its scene and in every load case's.
void setStep(DesignProblem& problem, double step) {
  problem.scene.settings.step = step;
  for (LoadCase& c : problem.load_cases) c.scene.settings.step = step;
}

}  // namespace

GradientReference referenceGradient(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                    const Eigen::VectorXd& x, double step) {
  GradientReference reference;
  reference.step = step;
  reference.functionals.push_back("cost");
  for (const ConstraintFunctional& f : functionals) reference.functionals.push_back(f.name);
  DesignProblem at = problem;
  setStep(at, step);
  timeMedian(1, [&] { reference.gradient = designGradient(reference.method, at, functionals, x); }, reference.seconds);
  return reference;
}

bool dependsOnDesign(const GradientReference& reference) {
  const DesignGradient& g = reference.gradient;
  const Eigen::Index design = g.cost.size() - 1;  // the last variable is b_{k+1}
  return !g.cost.head(design).isZero(0.0) || !g.constraints.leftCols(design).isZero(0.0);
}

PrecisionRun measureGradientRun(DesignProblem problem, const std::vector<ConstraintFunctional>& functionals,
                                const Eigen::VectorXd& x, const std::string& method, double step, double fd_step,
                                const GradientReference& reference, int repeat) {
  PrecisionRun result;
  result.variant = method;
  result.step = step;
  setStep(problem, step);
  std::optional<DesignGradient> gradient;
  try {
    timeMedian(repeat, [&] { gradient.emplace(designGradient(method, problem, functionals, x, fd_step)); },
               result.seconds);
  } catch (const SimulationError& e) {
    return failedRun(result, e);
  } catch (const std::invalid_argument& e) {
    return failedRun(result, e);
  }
  result.error = 0.0;
  const Eigen::Index design = x.size() - 1;  // the columns of the design variables, not b_{k+1}'s
  for (std::size_t r = 0; r < reference.functionals.size(); ++r) {
    const Eigen::Index row = static_cast<Eigen::Index>(r);
    const double error = relativeDifference(functionalGradient(*gradient, row).head(design),
                                            functionalGradient(reference.gradient, row).head(design));
    result.errors.emplace_back(reference.functionals[r], error);
    result.error = std::max(result.error, error);
  }
  return result;
}

}  // namespace mbsopt
