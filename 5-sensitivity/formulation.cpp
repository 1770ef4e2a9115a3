#include "mbsopt/sensitivity/formulation.hpp"

#include <stdexcept>

namespace mbsopt {

const std::vector<FormulationInfo>& formulations() {
  static const std::vector<FormulationInfo> registry{
      {"positive_part", "the paper's integral of the positive part, (15)-(16)", TimeMeasure::PositivePart},
      {"squared_positive_part", "the integral of the squared positive part: continuously differentiable",
       TimeMeasure::SquaredPositivePart},
      {"ks", "Kreisselmeier-Steinhauser over the time mean: smooth, at most the maximum, tending to it as rho grows",
       TimeMeasure::KsAggregate},
      {"grid_max", "the maximum over the time grid (a subgradient at a kink)", TimeMeasure::GridMax},
  };
  return registry;
}

std::vector<std::string> formulationNames() {
  std::vector<std::string> names;
  for (const FormulationInfo& info : formulations()) names.push_back(info.name);
  return names;
}

const FormulationInfo& formulation(const std::string& name) {
  for (const FormulationInfo& info : formulations())
    if (info.name == name) return info;
  std::string known;
  for (const FormulationInfo& info : formulations()) known += (known.empty() ? "" : ", ") + info.name;
  throw std::invalid_argument("unknown formulation '" + name + "' (known: " + known + ")");
}

const FormulationInfo& formulationOf(TimeMeasure measure) {
  for (const FormulationInfo& info : formulations())
    if (info.measure == measure) return info;
  throw std::invalid_argument("the problem's transcription is not one of the formulations");
}

}  // namespace mbsopt
