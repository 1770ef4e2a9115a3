#include "mbsopt/io/scene_parameters.hpp"

#include <algorithm>
#include <array>
#include <sstream>

#include "mbsopt/io/scene_text.hpp"

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
// model.ignore: the features a model file may leave out, comma-separated (`--set model.ignore=contacts,limits`).
constexpr std::array<const char*, 3> kWordSettings{"settings.closure", "settings.integrator", "model.ignore"};

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

using Visitor = std::function<void(const std::string&, const YamlNode&)>;

void walk(const std::string& prefix, const std::string& key, const YamlNode& node, const Visitor& visit) {
  if (node.isScalar()) {
    double value = 0.0;
    std::string why;
    if (parseNumber(node.text(), value, why)) visit(prefix, node);
  } else if (node.isSequence()) {
    const bool vector = isVectorKey(key) && node.size() == 3;
    for (std::size_t i = 0; i < node.size(); ++i)
      walk(prefix + "." + (vector ? kAxes[i] : std::to_string(i)), "", node[i], visit);
  } else if (node.isMap()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      if (node.key(i).isScalar()) walk(prefix + "." + node.key(i).text(), node.key(i).text(), node.value(i), visit);
  }
}

std::vector<std::string> split(const std::string& dotted) {
  std::vector<std::string> parts;
  std::istringstream in(dotted);
  for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
  return parts;
}

/// The map of the named entry `name` in any section, or nullptr.
YamlNode* namedEntry(YamlNode& root, const std::string& name) {
  for (std::size_t s = 0; s < root.size(); ++s) {
    if (!root.key(s).isScalar() || !isNamedSection(root.key(s).text()) || !root.value(s).isSequence()) continue;
    YamlNode& section = *root.find(root.key(s).text());
    for (std::size_t i = 0; i < section.size(); ++i) {
      YamlNode& entry = section.element(i);
      if (entry.isMap() && entry["name"].isScalar() && entry["name"].text() == name) return &entry;
    }
  }
  return nullptr;
}

/// A scalar without a place in the file (the loader names `--set` in its errors).
YamlNode unplaced(std::string text) { return {YamlNode::Kind::Scalar, {}, std::move(text)}; }

/// Writes a number the file leaves at its default (`settings.beta`, `hinge.q0`, `bob.com.x`,
/// `gravity.z`), creating the keys on the way; returns the node written, nullptr when the path
/// leads nowhere.
YamlNode* insertDefault(YamlNode& root, const std::vector<std::string>& parts, const std::string& value) {
  if (parts.empty()) return nullptr;
  YamlNode* node = &root;
  std::size_t first = 0;
  if (parts[0] != "settings" && parts[0] != "gravity" && parts[0] != "model") {
    node = namedEntry(root, parts[0]);
    if (node == nullptr) return nullptr;
    first = 1;
  }
  for (std::size_t i = first; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const bool last = i + 1 == parts.size();
    if (node->isSequence()) {
      const int axis = axisIndex(part);
      std::size_t index = 0;
      if (axis >= 0) index = static_cast<std::size_t>(axis);
      else if (!part.empty() && part.size() < 10 && std::all_of(part.begin(), part.end(), ::isdigit)) index = std::stoul(part);
      else return nullptr;
      if (index >= node->size()) return nullptr;
      node = &node->element(index);
    } else if (node->isMap()) {
      YamlNode* child = node->find(part);
      if (child == nullptr) {
        YamlNode fresh;
        if (last) {
          fresh = unplaced(value);
        } else if (isVectorKey(part) && axisIndex(parts[i + 1]) >= 0 && i + 2 == parts.size()) {
          fresh = YamlNode(YamlNode::Kind::Sequence, {});
          for (int axis = 0; axis < 3; ++axis) fresh.append(unplaced("0"));
        } else {
          fresh = YamlNode(YamlNode::Kind::Map, {});
        }
        child = &node->insert(unplaced(part), std::move(fresh));
      }
      node = child;
    } else {
      return nullptr;
    }
  }
  if (!node->isScalar()) return nullptr;
  node->assign(value);
  return node;
}

}  // namespace

void forEachNumber(const YamlNode& root, const Visitor& visit) {
  if (!root.isMap()) return;
  for (std::size_t s = 0; s < root.size(); ++s) {
    if (!root.key(s).isScalar()) continue;
    const std::string& key = root.key(s).text();
    const YamlNode& section = root.value(s);
    if (!isNamedSection(key)) {
      walk(key, key, section, visit);
      continue;
    }
    if (!section.isSequence()) continue;
    for (std::size_t i = 0; i < section.size(); ++i) {
      const YamlNode& entry = section[i];
      if (!entry.isMap()) continue;
      const YamlNode& name = entry["name"];
      const std::string owner = name.isScalar() ? name.text() : key + "." + std::to_string(i);
      for (std::size_t f = 0; f < entry.size(); ++f)
        if (entry.key(f).isScalar() && entry.key(f).text() != "name")
          walk(owner + "." + entry.key(f).text(), entry.key(f).text(), entry.value(f), visit);
    }
  }
}

bool isWordSetting(const std::string& dotted_name) {
  return std::any_of(kWordSettings.begin(), kWordSettings.end(), [&](const char* s) { return dotted_name == s; });
}

SceneError unknownOverride(const YamlContext& context, const ParameterOverride& o, const std::vector<std::string>& names) {
  return SceneError(context.path(), 0, 0,
                    describe(o) + ": the scene has no number named " + quoted(o.name) + suggestion(o.name, names) +
                        "; 'mbsopt parameters SCENE' lists them");
}

std::vector<ParameterOverride> applyOverrides(YamlContext& context, YamlNode& root,
                                              const std::vector<ParameterOverride>& overrides) {
  std::vector<ParameterOverride> for_the_model_file;
  const bool model_file = root.isMap() && root["model"].isDefined();
  for (const ParameterOverride& o : overrides) {
    const YamlNode* target = nullptr;
    std::vector<std::string> names;
    forEachNumber(root, [&](const std::string& name, const YamlNode& node) {
      if (name == o.name && target == nullptr) target = &node;
      names.push_back(name);
    });
    // A word setting is no number of the file: it is written in (or over) like a default.
    const std::string text = o.word.empty() ? formatNumber(o.value) : o.word;
    YamlNode* written = nullptr;
    if (target != nullptr) {
      written = const_cast<YamlNode*>(target);  // a node of `root`, which is ours to change
      written->assign(text);
    } else if (!root.isMap() || (written = insertDefault(root, split(o.name), text)) == nullptr) {
      if (!model_file || !o.word.empty()) throw unknownOverride(context, o, names);
      for_the_model_file.push_back(o);
      continue;
    }
    context.markOverridden(*written, describe(o));
  }
  return for_the_model_file;
}

std::string describe(const ParameterOverride& o) {
  return o.origin + " " + o.name + "=" + (o.word.empty() ? formatNumber(o.value) : o.word);
}

}  // namespace mbsopt
