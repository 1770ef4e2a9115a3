#include "app/design_point.hpp"

#include <cctype>

namespace mbsopt {

std::vector<CLI::Option*> addDesignPointOptions(CLI::App& command, DesignPointRequest& request,
                                                const std::string& condition) {
  const auto help = [&](std::string text) {  // "With --gradients: the ...", or "The ..."
    if (condition.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
    return condition + text;
  };
  CLI::Option* design = command.add_option("--design", request.design,
                     help("the design variables in SI units, comma-separated, in the problem's order, each within its "
                          "bounds and checked as the scene file checks the same number (default: the scene's values)"))
      ->delimiter(',');
  CLI::Option* artificial = command.add_option(
      "--artificial", request.artificial,
      help("the artificial variable b_{k+1} in the cost's units, within design.artificial's bounds (default: the "
           "problem's start); below the cost's peak it makes the cost's constraint active"));
  CLI::Option* outside = command.add_flag(
      "--outside-bounds", request.outside_bounds,
      help("evaluate a --design or --artificial outside the design's bounds (the output says which values are); values the scene "
           "refuses, such as a negative stiffness, stay refused"));
  return {design, artificial, outside};
}

}  // namespace mbsopt
