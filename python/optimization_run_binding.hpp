// An optimisation run as Python sees it (`mbsopt.OptimizationRun`): the library's OptimizationRun
// with attributes and numpy arrays, its status and reported point as enums, and record(), the JSON
// record `mbsopt optimize --json` writes.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "mbsopt/design/optimization_run.hpp"

namespace mbsopt {

struct PythonRun {
  OptimizationRun run;
  std::string problem;  ///< the scene file the problem came from (the record's `problem`)
};

/// Adds Status, ReportedPoint, Verdict, History and OptimizationRun to the module.
void bindOptimizationRun(pybind11::module_& m);

}  // namespace mbsopt
