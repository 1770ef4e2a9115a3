// The dotted names of the numbers of a scene file (problems/scenes/README.md, "Dotted parameter
// names"): `bob.mass`, `arm.translation.z`, `crank.motion.polynomial.1`, `settings.step`.
#pragma once

#include <functional>
#include <string>
#include <vector>
#include "mbsopt/io/yaml_document.hpp"

#include "mbsopt/io/yaml_reader.hpp"

namespace mbsopt {

/// Calls `visit(name, node)` for every number of the scene, in file order.
void forEachNumber(const YamlNode& root, const std::function<void(const std::string&, const YamlNode&)>& visit);

/// Replaces the numbers (and word settings) named by the overrides in the parsed scene. A number the file leaves at
/// its default (`settings.beta`, `hinge.q0`, `bob.com.x`) is written in, so the loader checks it
/// like any other; a name that leads nowhere is an error naming the override.
void applyOverrides(YamlContext& context, YamlNode& root, const std::vector<ParameterOverride>& overrides);

/// "--set name=value" (ParameterOverride::origin, name and value), for messages.
std::string describe(const ParameterOverride& override_);

}  // namespace mbsopt
