#include "mbsopt/io/design_point.hpp"

#include <cmath>
#include <stdexcept>

#include "mbsopt/io/scene_text.hpp"

namespace mbsopt {

Eigen::VectorXd checkedDesignPoint(const SceneSource& source, const std::vector<ParameterOverride>& overrides,
                                   const DesignProblem& problem, const DesignPointRequest& request) {
  Eigen::VectorXd x = initialPoint(problem);
  const std::vector<DesignVariable>& variables = problem.design.variables;
  const std::vector<double>& design = request.design;
  const auto refuse = [&](const std::string& what) { throw std::invalid_argument(source.path + ": " + what); };
  if (!design.empty()) {
    if (design.size() != variables.size())
      refuse("the design point has " + std::to_string(design.size()) + " values for " +
             std::to_string(variables.size()) + " design variables");
    std::vector<ParameterOverride> with_design = overrides;
    for (std::size_t i = 0; i < variables.size(); ++i) {
      const DesignVariable& v = variables[i];
      const double value = design[i];
      if (!std::isfinite(value))
        refuse("the design point's value " + std::to_string(i + 1) + " (" + v.parameter + ") is " + formatNumber(value) +
               ", not a finite number");
      if (!request.outside_bounds && (value < v.lower || value > v.upper))
        refuse("the design point's " + v.parameter + " = " + formatNumber(value) + " lies outside its bounds [" +
               formatNumber(v.lower) + ", " + formatNumber(v.upper) +
               "] (design.variables." + std::to_string(i) + "); evaluating it there must be asked for explicitly");
      x[static_cast<Eigen::Index>(i)] = value / v.scale;
      if (!std::isfinite(x[static_cast<Eigen::Index>(i)]))
        refuse("the design point's " + v.parameter + " = " + formatNumber(value) + " is beyond the range of its scale " +
               formatNumber(v.scale));
      with_design.emplace_back(v.parameter, value);
      with_design.back().origin = "the design point";
      // Outside its bounds (allowed), the bounds widened to take it: the scene checks the value itself.
      const std::string bounds = "design.variables." + std::to_string(i);
      if (value < v.lower) with_design.emplace_back(bounds + ".lower", value);
      if (value > v.upper) with_design.emplace_back(bounds + ".upper", value);
    }
    try {
      loadScene(source, with_design);  // the scene's own checks of each value
    } catch (const SceneError& e) {
      throw std::invalid_argument(e.path() + ":" + std::to_string(e.line()) + ":" + std::to_string(e.column()) + ": " +
                                  e.reason());
    }
  }
  if (request.artificial) {
    const double value = *request.artificial;
    const ArtificialVariable& b = problem.design.artificial;
    if (!std::isfinite(value)) refuse("the design point's b_{k+1} = " + formatNumber(value) + " is not a finite number");
    if (!request.outside_bounds && (value < b.lower || value > b.upper))
      refuse("the design point's b_{k+1} = " + formatNumber(value) + " lies outside its bounds [" +
             formatNumber(b.lower) + ", " + formatNumber(b.upper) +
             "] (design.artificial); evaluating it there must be asked for explicitly");
    x[x.size() - 1] = value / b.scale;
    if (!std::isfinite(x[x.size() - 1]))
      refuse("the design point's b_{k+1} = " + formatNumber(value) + " is beyond the range of its scale " +
             formatNumber(b.scale));
  }
  return x;
}

std::vector<std::string> outsideBounds(const DesignProblem& problem, const Eigen::VectorXd& x) {
  std::vector<std::string> out;
  const std::vector<DesignVariable>& variables = problem.design.variables;
  for (std::size_t i = 0; i < variables.size(); ++i) {
    const DesignVariable& v = variables[i];
    const double value = x[static_cast<Eigen::Index>(i)] * v.scale;
    if (value < v.lower) out.push_back(v.parameter + " = " + formatNumber(value) + " below its lower bound " + formatNumber(v.lower));
    if (value > v.upper) out.push_back(v.parameter + " = " + formatNumber(value) + " above its upper bound " + formatNumber(v.upper));
  }
  const ArtificialVariable& b = problem.design.artificial;
  const double value = x[x.size() - 1] * b.scale;
  if (value < b.lower) out.push_back("b_{k+1} = " + formatNumber(value) + " below its lower bound " + formatNumber(b.lower));
  if (value > b.upper) out.push_back("b_{k+1} = " + formatNumber(value) + " above its upper bound " + formatNumber(b.upper));
  return out;
}

}  // namespace mbsopt
