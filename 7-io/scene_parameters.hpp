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
/// like any other; a name that leads nowhere is an error naming the override, unless the scene has a
/// `model` file: such overrides are returned, for the model's own parameters and starts
/// (applyModelFileOverrides), once the file is read.
std::vector<ParameterOverride> applyOverrides(YamlContext& context, YamlNode& root,
                                              const std::vector<ParameterOverride>& overrides);

/// The error of an override whose name leads nowhere; `names` are those that lead somewhere.
SceneError unknownOverride(const YamlContext& context, const ParameterOverride& o, const std::vector<std::string>& names);

/// "--set name=value" (ParameterOverride::origin, name and value), for messages.
std::string describe(const ParameterOverride& override_);

}  // namespace mbsopt
