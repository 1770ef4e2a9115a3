// The `design:` section of a scene file (problems/scenes/README.md, "Design problems").
#pragma once

#include "sensitivity/design_problem.hpp"
#include "problems/yaml_reader.hpp"

namespace mbsopt {

/// Reads the section; names (parameters, sensors) are checked against the built model, every error
/// at its line.
DesignDescription readDesign(const MapReader& design, const Model& model);

}  // namespace mbsopt
