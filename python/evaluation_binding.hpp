// A design problem evaluated at one point as Python sees it (`mbsopt.Evaluation`): the library's
// NlpEvaluation with the names of its columns and rows, as attributes and numpy arrays.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "mbsopt/optimizers/nlp_problem.hpp"

namespace mbsopt {

struct PythonEvaluation {
  NlpEvaluation values;
  bool gradients = false;                  ///< whether values holds the gradients
  std::vector<std::string> variables;      ///< the design variables' parameters, then b_{k+1}
  std::vector<double> scales;              ///< value = x · scale, per variable
  std::vector<std::string> constraint_names;
  std::vector<std::string> outside_bounds;  ///< the design values an evaluation outside the bounds let through
};

/// Adds Evaluation to the module.
void bindEvaluation(pybind11::module_& m);

}  // namespace mbsopt
