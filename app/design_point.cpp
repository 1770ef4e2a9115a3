#include "app/design_point.hpp"

#include <cctype>
#include <cmath>
#include <string>

#include "mbsopt/problems/scene_text.hpp"

namespace mbsopt {

std::pair<CLI::Option*, CLI::Option*> addDesignPointOptions(CLI::App& command, DesignPointArgument& argument,
                                                            const std::string& condition) {
  const auto help = [&](std::string text) {  // "With --gradients: the ...", or "The ..."
    if (condition.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
    return condition + text;
  };
  CLI::Option* design = command.add_option("--design", argument.design,
                                           help("the design variables in SI units, comma-separated, in the "
                                                "problem's order (default: the scene's values)"))
                            ->delimiter(',');
  CLI::Option* artificial = command.add_option(
      "--artificial", argument.artificial,
      help("the artificial variable b_{k+1} in the cost's units (default: the problem's); below the cost's peak it makes the cost's "
           "constraint active"));
  return {design, artificial};
}

Eigen::VectorXd designPoint(const SceneSource& source, const DesignProblem& problem, const DesignPointArgument& argument) {
  Eigen::VectorXd x = initialPoint(problem);
  const auto& variables = problem.design.variables;
  const std::vector<double>& design = argument.design;
  if (!design.empty()) {
    if (design.size() != variables.size())
      throw SceneError(source.path, 0, 0,
                       "--design: " + std::to_string(design.size()) + " values for " +
                           std::to_string(variables.size()) + " design variables");
    for (std::size_t i = 0; i < variables.size(); ++i) {
      if (!std::isfinite(design[i]))
        throw SceneError(source.path, 0, 0,
                         "--design: value " + std::to_string(i + 1) + " (" + variables[i].parameter + ") is " +
                             formatNumber(design[i]) + ", not a finite number");
      x[static_cast<Eigen::Index>(i)] = design[i] / variables[i].scale;
    }
  }
  if (argument.artificial) {
    if (!std::isfinite(*argument.artificial))
      throw SceneError(source.path, 0, 0, "--artificial: " + formatNumber(*argument.artificial) + " is not a finite number");
    x[x.size() - 1] = *argument.artificial / problem.design.artificial.scale;
  }
  return x;
}

}  // namespace mbsopt
