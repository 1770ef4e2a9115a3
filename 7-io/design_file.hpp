// The `design:` section of a scene file (problems/scenes/README.md, "Design problems").
#pragma once

#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/io/yaml_reader.hpp"

namespace mbsopt {

/// Reads the section; names (parameters, sensors) are checked against the built model, every error
/// at its line.
DesignDescription readDesign(const MapReader& design, const Model& model);

/// Once the scene is assembled: every cut reaction the section reads (its cost's and constraints'
/// `sensor:`) must be determinate at the initial state (reactionDeterminacyDefect), an error at that
/// `sensor:` otherwise; and the transcription's windows (as readDesign read them into `described`)
/// must hold two time points each, an error at `windows:` otherwise.
void checkDesignAgainstScene(const MapReader& design, const DesignDescription& described, const Scene& scene);

}  // namespace mbsopt
