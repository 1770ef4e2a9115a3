// The formulations by name (one registry): how a max-over-time constraint, and the cost's epigraph
// b_{k+1} ≥ |y(t)|, become one number each (time_functional.hpp's measures). A design file's
// `transcription.measure`, --formulation and the Python module take these names.
#pragma once

#include <string>
#include <vector>

#include "mbsopt/sensitivity/time_functional.hpp"

namespace mbsopt {

struct FormulationInfo {
  std::string name;
  std::string description;  ///< one sentence, for --help and the docs
  TimeMeasure measure;
};

/// positive_part, squared_positive_part, ks, grid_max.
const std::vector<FormulationInfo>& formulations();
/// The registered formulation `name`; std::invalid_argument listing the names otherwise.
const FormulationInfo& formulation(const std::string& name);
/// The formulation whose measure is `measure`; std::invalid_argument where none is (an exact functional).
const FormulationInfo& formulationOf(TimeMeasure measure);
/// The registered names, in the registry's order.
std::vector<std::string> formulationNames();

}  // namespace mbsopt
