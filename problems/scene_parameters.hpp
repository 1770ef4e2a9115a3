// The dotted names of the numbers of a scene file (problems/scenes/README.md, "Dotted parameter
// names"): `bob.mass`, `arm.translation.z`, `crank.motion.polynomial.1`, `settings.step`.
#pragma once

#include <functional>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "problems/yaml_reader.hpp"

namespace mbsopt {

/// Calls `visit(name, node)` for every number of the scene, in file order.
void forEachNumber(const YAML::Node& root, const std::function<void(const std::string&, const YAML::Node&)>& visit);

/// Replaces the numbers named by the overrides in the parsed scene; returns the overrides that name
/// no number of the file (a model parameter left at its default, or a mistake).
std::vector<ParameterOverride> applyOverrides(YamlContext& context, YAML::Node& root,
                                              const std::vector<ParameterOverride>& overrides);

/// The shortest text that reads back as the same double.
std::string formatNumber(double value);
/// "--set name=value", for messages.
std::string describe(const ParameterOverride& override_);

}  // namespace mbsopt
