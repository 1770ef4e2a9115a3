#include "problems/scene_parameters.hpp"

#include <algorithm>
#include <array>
#include <sstream>

#include "problems/scene_text.hpp"

namespace mbsopt {

namespace {

// Keys whose value is a vector [x, y, z]: its components are named .x, .y, .z; the entries of any
// other list by their index.
constexpr std::array<const char*, 10> kVectorKeys{"gravity", "translation", "axis",      "com",       "point",
                                                  "point_a", "point_b",     "axis_in_a", "axis_in_b", "origin"};
// Sections that list named entries; an entry's numbers are named after its `name`.
constexpr std::array<const char*, 6> kNamedSections{"tracks", "elements", "bodies", "forces", "cuts", "sensors"};
constexpr std::array<const char*, 3> kAxes{"x", "y", "z"};
// Settings whose value is a word (problems/scenes/README.md, "Top level"); the loader checks the word.
constexpr std::array<const char*, 1> kWordSettings{"settings.closure"};

bool isVectorKey(const std::string& key) {
  return std::any_of(kVectorKeys.begin(), kVectorKeys.end(), [&](const char* k) { return key == k; });
}

bool isNamedSection(const std::string& key) {
  return std::any_of(kNamedSections.begin(), kNamedSections.end(), [&](const char* s) { return key == s; });
}

int axisIndex(const std::string& part) {
  for (int i = 0; i < 3; ++i)
    if (part == kAxes[static_cast<std::size_t>(i)]) return i;
  return -1;
}

using Visitor = std::function<void(const std::string&, const YAML::Node&)>;

void walk(const std::string& prefix, const std::string& key, const YAML::Node& node, const Visitor& visit) {
  if (node.IsScalar()) {
    double value = 0.0;
    std::string why;
    if (parseNumber(node.Scalar(), value, why)) visit(prefix, node);
  } else if (node.IsSequence()) {
    const bool vector = isVectorKey(key) && node.size() == 3;
    for (std::size_t i = 0; i < node.size(); ++i)
      walk(prefix + "." + (vector ? kAxes[i] : std::to_string(i)), "", node[i], visit);
  } else if (node.IsMap()) {
    for (const auto& entry : node)
      if (entry.first.IsScalar()) walk(prefix + "." + entry.first.Scalar(), entry.first.Scalar(), entry.second, visit);
  }
}

std::vector<std::string> split(const std::string& dotted) {
  std::vector<std::string> parts;
  std::istringstream in(dotted);
  for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
  return parts;
}

/// The map of the named entry `name` in any section, or an invalid node.
YAML::Node namedEntry(const YAML::Node& root, const std::string& name) {
  for (const auto& section : root) {
    if (!section.first.IsScalar() || !isNamedSection(section.first.Scalar()) || !section.second.IsSequence()) continue;
    for (const YAML::Node& entry : section.second)
      if (entry.IsMap() && entry["name"].IsScalar() && entry["name"].Scalar() == name) return entry;
  }
  return YAML::Node(YAML::NodeType::Undefined);
}

/// Writes a number the file leaves at its default (`settings.beta`, `hinge.q0`, `bob.com.x`,
/// `gravity.z`), creating the keys on the way. False when the path leads nowhere.
bool insertDefault(YAML::Node& root, const std::vector<std::string>& parts, const std::string& value,
                   YAML::Node& written) {
  if (parts.empty()) return false;
  YAML::Node node = root;
  std::size_t first = 0;
  if (parts[0] != "settings" && parts[0] != "gravity") {
    const YAML::Node entry = namedEntry(root, parts[0]);
    if (!entry.IsDefined()) return false;
    node.reset(entry);
    first = 1;
  }
  for (std::size_t i = first; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    if (node.IsSequence()) {
      const int axis = axisIndex(part);
      std::size_t index = 0;
      if (axis >= 0) index = static_cast<std::size_t>(axis);
      else if (!part.empty() && std::all_of(part.begin(), part.end(), ::isdigit)) index = std::stoul(part);
      else return false;
      if (index >= node.size()) return false;
      YAML::Node child = node[index];
      node.reset(child);
    } else if (node.IsMap()) {
      if (!node[part].IsDefined()) {
        if (last) node[part] = value;
        else if (isVectorKey(part) && axisIndex(parts[i + 1]) >= 0 && i + 2 == parts.size())
          node[part] = std::vector<std::string>{"0", "0", "0"};
        else node[part] = YAML::Node(YAML::NodeType::Map);
      }
      YAML::Node child = node[part];
      node.reset(child);
    } else {
      return false;
    }
  }
  if (!node.IsScalar()) return false;
  node = value;
  written.reset(node);
  return true;
}

}  // namespace

void forEachNumber(const YAML::Node& root, const Visitor& visit) {
  if (!root.IsMap()) return;
  for (const auto& section : root) {
    if (!section.first.IsScalar()) continue;
    const std::string& key = section.first.Scalar();
    if (!isNamedSection(key)) {
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

bool isWordSetting(const std::string& dotted_name) {
  return std::any_of(kWordSettings.begin(), kWordSettings.end(), [&](const char* s) { return dotted_name == s; });
}

void applyOverrides(YamlContext& context, YAML::Node& root, const std::vector<ParameterOverride>& overrides) {
  for (const ParameterOverride& o : overrides) {
    std::vector<YAML::Node> targets;
    std::vector<std::string> names;
    forEachNumber(root, [&](const std::string& name, const YAML::Node& node) {
      if (name == o.name) targets.push_back(node);
      names.push_back(name);
    });
    // A word setting is no number of the file: it is written in (or over) like a default.
    const std::string text = o.word.empty() ? formatNumber(o.value) : o.word;
    YAML::Node written;
    if (!targets.empty()) {
      written.reset(targets.front());
      written = text;
    } else if (!root.IsMap() || !insertDefault(root, split(o.name), text, written)) {
      throw SceneError(context.path(), 0, 0,
                       describe(o) + ": the scene has no number named " + quoted(o.name) + suggestion(o.name, names) +
                           "; 'mbsopt parameters SCENE' lists them");
    }
    context.markOverridden(written, describe(o));
  }
}

std::string describe(const ParameterOverride& o) {
  return "--set " + o.name + "=" + (o.word.empty() ? formatNumber(o.value) : o.word);
}

}  // namespace mbsopt
