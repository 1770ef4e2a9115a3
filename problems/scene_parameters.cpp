#include "problems/scene_parameters.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace mbsopt {

namespace {

// Keys whose value is a vector [x, y, z]: its components are named .x, .y, .z; the entries of any
// other list by their index.
constexpr std::array<const char*, 10> kVectorKeys{"gravity", "translation", "axis",      "com",       "point",
                                                  "point_a", "point_b",     "axis_in_a", "axis_in_b", "origin"};
// Sections that list named entries; an entry's numbers are named after its `name`.
constexpr std::array<const char*, 6> kNamedSections{"tracks", "elements", "bodies", "forces", "cuts", "sensors"};

bool isVectorKey(const std::string& key) {
  return std::any_of(kVectorKeys.begin(), kVectorKeys.end(), [&](const char* k) { return key == k; });
}

using Visitor = std::function<void(const std::string&, const YAML::Node&)>;

void walk(const std::string& prefix, const std::string& key, const YAML::Node& node, const Visitor& visit) {
  if (node.IsScalar()) {
    double value = 0.0;
    std::string why;
    if (parseNumber(node.Scalar(), value, why)) visit(prefix, node);
  } else if (node.IsSequence()) {
    static constexpr std::array<const char*, 3> kAxes{"x", "y", "z"};
    const bool vector = isVectorKey(key) && node.size() == 3;
    for (std::size_t i = 0; i < node.size(); ++i)
      walk(prefix + "." + (vector ? kAxes[i] : std::to_string(i)), "", node[i], visit);
  } else if (node.IsMap()) {
    for (const auto& entry : node)
      if (entry.first.IsScalar()) walk(prefix + "." + entry.first.Scalar(), entry.first.Scalar(), entry.second, visit);
  }
}

}  // namespace

void forEachNumber(const YAML::Node& root, const Visitor& visit) {
  if (!root.IsMap()) return;
  for (const auto& section : root) {
    if (!section.first.IsScalar()) continue;
    const std::string& key = section.first.Scalar();
    const bool named = std::any_of(kNamedSections.begin(), kNamedSections.end(), [&](const char* s) { return key == s; });
    if (!named) {
      walk(key, key, section.second, visit);
      continue;
    }
    if (!section.second.IsSequence()) continue;
    for (std::size_t i = 0; i < section.second.size(); ++i) {
      const YAML::Node entry = section.second[i];
      if (!entry.IsMap()) continue;
      const YAML::Node name = entry["name"];
      const std::string owner = name.IsScalar() ? name.Scalar() : key + "." + std::to_string(i);
      for (const auto& field : entry)
        if (field.first.IsScalar() && field.first.Scalar() != "name")
          walk(owner + "." + field.first.Scalar(), field.first.Scalar(), field.second, visit);
    }
  }
}

std::vector<ParameterOverride> applyOverrides(YamlContext& context, YAML::Node& root,
                                              const std::vector<ParameterOverride>& overrides) {
  std::vector<ParameterOverride> unmatched;
  for (const ParameterOverride& o : overrides) {
    std::vector<YAML::Node> targets;
    forEachNumber(root, [&](const std::string& name, const YAML::Node& node) {
      if (name == o.name) targets.push_back(node);
    });
    if (targets.empty()) {
      unmatched.push_back(o);
      continue;
    }
    YAML::Node target = targets.front();
    target = formatNumber(o.value);
    context.markOverridden(target, describe(o));
  }
  return unmatched;
}

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string describe(const ParameterOverride& o) { return "--set " + o.name + "=" + formatNumber(o.value); }

}  // namespace mbsopt
