#include "problems/yaml_reader.hpp"

#include "problems/scene_text.hpp"

#include <algorithm>
#include <cmath>

namespace mbsopt {

namespace {

std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return quoted(node.Scalar());
}

std::string listOf(std::initializer_list<const char*> words) {
  std::string text;
  for (const char* word : words) text += (text.empty() ? "" : ", ") + std::string(word);
  return text;
}

}  // namespace

namespace {

bool contains(const YAML::Node& tree, const YAML::Node& node) {
  if (tree.is(node)) return true;
  if (tree.IsSequence())
    for (const YAML::Node& child : tree)
      if (contains(child, node)) return true;
  if (tree.IsMap())
    for (const auto& child : tree)
      if (contains(child.second, node)) return true;
  return false;
}

}  // namespace

void YamlContext::fail(const YAML::Node& node, const std::string& what) const { fail(node, node.Mark(), what); }

void YamlContext::fail(const YAML::Node& node, const YAML::Mark& mark, const std::string& what) const {
  std::string origin;  // the overrides inside the failing node may be the cause
  for (const auto& [overridden, text] : overridden_)
    if (contains(node, overridden)) origin += (origin.empty() ? " (value from " : ", ") + text;
  fail(mark, what + (origin.empty() ? "" : origin + ")"));
}

void YamlContext::fail(const YAML::Mark& mark, const std::string& what) const {
  if (mark.is_null()) throw SceneError(path_, 0, 0, what);
  throw SceneError(path_, mark.line + 1, mark.column + 1, what);
}

void YamlContext::markOverridden(const YAML::Node& node, std::string origin) {
  overridden_.emplace_back(node, std::move(origin));
}

double readNumber(const YamlContext& context, const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) context.fail(node, what + ": expected a number, got " + describe(node));
  const std::string& text = node.Scalar();
  if (text == ".nan" || text == ".NaN" || text == ".NAN" || text.ends_with(".inf") || text.ends_with(".Inf") ||
      text.ends_with(".INF"))
    context.fail(node, what + ": " + quoted(text) + " is not a finite number");
  double value = 0.0;
  std::string why;
  if (!parseNumber(text, value, why)) context.fail(node, what + ": " + why);
  return value;
}

MapReader::MapReader(const YamlContext& context, const YAML::Node& node, std::string what)
    : context_(context), node_(node), what_(std::move(what)) {
  if (!node.IsMap()) context.fail(node, what_ + ": expected a map of 'key: value', got " + describe(node));
  std::set<std::string> seen;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) context.fail(entry.first, what_ + ": keys must be plain words");
    if (!seen.insert(entry.first.Scalar()).second)
      context.fail(entry.first, what_ + ": duplicate key " + quoted(entry.first.Scalar()));
  }
}

void MapReader::allowKeys(std::initializer_list<const char*> keys) const {
  for (const auto& entry : node_) {
    const std::string& key = entry.first.Scalar();
    if (std::any_of(keys.begin(), keys.end(), [&](const char* allowed) { return key == allowed; })) continue;
    context_.fail(entry.second, entry.first.Mark(), what_ + ": unknown key " + quoted(key) + suggestion(key, {keys.begin(), keys.end()}) +
                                   "; allowed keys: " + listOf(keys));
  }
}

bool MapReader::has(const std::string& key) const { return node_[key].IsDefined(); }

YAML::Node MapReader::required(const std::string& key) const {
  const YAML::Node value = node_[key];
  if (!value.IsDefined()) context_.fail(node_, what_ + ": missing required key '" + key + "'");
  return value;
}

YAML::Mark MapReader::markOf(const std::string& key) const {
  const YAML::Node value = node_[key];
  return value.IsDefined() && !value.Mark().is_null() ? value.Mark() : node_.Mark();
}

void MapReader::fail(const std::string& key, const std::string& what) const {
  const YAML::Node value = node_[key];
  if (value.IsDefined()) context_.fail(value, what_ + ": " + what);
  context_.fail(node_, what_ + ": " + what);
}

double MapReader::number(const std::string& key) const { return readNumber(context_, required(key), what_ + ": " + key); }

double MapReader::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

double MapReader::positive(const std::string& key) const {
  const double value = number(key);
  if (!(value > 0.0)) fail(key, key + " must be positive, got " + formatNumber(value));
  return value;
}

double MapReader::nonNegative(const std::string& key, double fallback) const {
  const double value = number(key, fallback);
  if (value < 0.0) fail(key, key + " must not be negative, got " + formatNumber(value));
  return value;
}

int MapReader::positiveInteger(const std::string& key, int fallback) const {
  if (!has(key)) return fallback;
  const double value = number(key);
  if (!(value >= 1.0 && value <= 1e6 && value == std::floor(value)))
    fail(key, key + " must be a positive integer, got " + formatNumber(value));
  return static_cast<int>(value);
}

Eigen::Vector3d MapReader::vector(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() != 3)
    fail(key, key + ": expected a vector [x, y, z], got " +
                  (value.IsSequence() ? "a list of " + std::to_string(value.size()) : describe(value)));
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = readNumber(context_, value[i], what_ + ": " + key);
  return v;
}

Eigen::Vector3d MapReader::vector(const std::string& key, const Eigen::Vector3d& fallback) const {
  return has(key) ? vector(key) : fallback;
}

std::string MapReader::name(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsScalar()) fail(key, key + ": expected a name, got " + describe(value));
  const std::string& text = value.Scalar();
  const bool valid = !text.empty() && (std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_') &&
                     std::all_of(text.begin(), text.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  if (!valid) fail(key, key + ": " + quoted(text) + " is not a valid name (a letter or '_', then letters, digits, '_')");
  return text;
}

std::string MapReader::choice(const std::string& key, std::initializer_list<const char*> choices,
                              const char* fallback) const {
  if (!has(key) && *fallback) return fallback;
  const YAML::Node value = required(key);
  if (value.IsScalar())
    for (const char* choice : choices)
      if (value.Scalar() == choice) return choice;
  fail(key, key + ": expected one of " + listOf(choices) + ", got " + describe(value));
}

void rejectAliases(const YamlContext& context, const YAML::Node& root) {
  // A node reached twice is an alias of an anchor: each node has its own position in the text.
  std::set<int> seen;
  std::vector<YAML::Node> pending{root};
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (!node.IsNull() && !node.Mark().is_null() && !seen.insert(node.Mark().pos).second)
      context.fail(node, "this value is anchored ('&name') and reused by an alias ('*name'); a scene refuses "
                         "aliases, so that every number has one name of its own");
    if (node.IsSequence())
      for (const YAML::Node& child : node) pending.push_back(child);
    if (node.IsMap())
      for (const auto& child : node) pending.push_back(child.second);
  }
}

std::vector<YAML::Node> readList(const YamlContext& context, const YAML::Node& node, const std::string& what) {
  if (!node.IsDefined() || node.IsNull()) return {};
  if (!node.IsSequence()) context.fail(node, what + ": expected a list of entries ('- ...'), got " + describe(node));
  return {node.begin(), node.end()};
}

}  // namespace mbsopt
