// A simulation as Python sees it (`mbsopt.Simulation`): the library's Integration with the scene's
// names and units beside it, as attributes and numpy arrays (a row per time point).
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "mbsopt/integrators/integration.hpp"

namespace mbsopt {

struct PythonSimulation {
  Integration integration;
  std::string integrator;  ///< the integrator's registered name
  std::vector<std::string> coordinates, coordinate_units, sensor_names, sensor_units;
};

/// Adds ErrorEstimate and Simulation to the module.
void bindSimulation(pybind11::module_& m);

}  // namespace mbsopt
