#include "app/design_point.hpp"

#include <string>

namespace mbsopt {

Eigen::VectorXd designPoint(const SceneSource& source, const DesignProblem& problem, const std::vector<double>& design,
                            const std::optional<double>& artificial) {
  Eigen::VectorXd x = initialPoint(problem);
  const auto& variables = problem.design.variables;
  if (!design.empty()) {
    if (design.size() != variables.size())
      throw SceneError(source.path, 0, 0,
                       "--design: " + std::to_string(design.size()) + " values for " +
                           std::to_string(variables.size()) + " design variables");
    for (std::size_t i = 0; i < variables.size(); ++i)
      x[static_cast<Eigen::Index>(i)] = design[i] / variables[i].scale;
  }
  if (artificial) x[x.size() - 1] = *artificial / problem.design.artificial.scale;
  return x;
}

}  // namespace mbsopt
