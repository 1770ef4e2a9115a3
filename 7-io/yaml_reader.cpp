#include "mbsopt/io/yaml_reader.hpp"

#include <algorithm>
#include <cmath>

#include "mbsopt/io/scene_text.hpp"

namespace mbsopt {

namespace {

std::string describe(const YamlNode& node) {
  if (!node.isDefined() || node.isNull()) return "nothing";
  if (node.isSequence()) return "a list";
  if (node.isMap()) return "a map";
  return quoted(node.text());
}

template <class Words>
std::string listOf(const Words& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : ", ") + std::string(word);
  return text;
}

}  // namespace

namespace {

bool contains(const YamlNode& tree, const YamlNode* node) {
  if (&tree == node) return true;
  for (std::size_t i = 0; i < tree.size(); ++i)
    if (contains(tree.isMap() ? tree.value(i) : tree[i], node)) return true;
  return false;
}

}  // namespace

void YamlContext::fail(const YamlNode& node, const std::string& what) const { fail(node, node.mark(), what); }

void YamlContext::fail(const YamlNode& node, const YamlMark& mark, const std::string& what) const {
  std::string origin;  // the overrides inside the failing node may be the cause
  for (const auto& [overridden, text] : overridden_)
    if (contains(node, overridden)) origin += (origin.empty() ? " (value from " : ", ") + text;
  fail(mark, what + (origin.empty() ? "" : origin + ")"));
}

void YamlContext::fail(const YamlMark& mark, const std::string& what) const {
  if (mark.isNull()) throw SceneError(path_, 0, 0, what);
  throw SceneError(path_, mark.line + 1, mark.column + 1, what);
}

void YamlContext::markOverridden(const YamlNode& node, std::string origin) {
  overridden_.emplace_back(&node, std::move(origin));
}

double readNumber(const YamlContext& context, const YamlNode& node, const std::string& what) {
  if (!node.isScalar()) context.fail(node, what + ": expected a number, got " + describe(node));
  const std::string& text = node.text();
  if (text == ".nan" || text == ".NaN" || text == ".NAN" || text.ends_with(".inf") || text.ends_with(".Inf") ||
      text.ends_with(".INF"))
    context.fail(node, what + ": " + quoted(text) + " is not a finite number");
  double value = 0.0;
  std::string why;
  if (!parseNumber(text, value, why)) context.fail(node, what + ": " + why);
  return value;
}

MapReader::MapReader(const YamlContext& context, const YamlNode& node, std::string what)
    : context_(context), node_(node), what_(std::move(what)) {
  if (!node.isMap()) context.fail(node, what_ + ": expected a map of 'key: value', got " + describe(node));
  std::set<std::string> seen;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YamlNode& key = node.key(i);
    if (!key.isScalar()) context.fail(key, what_ + ": keys must be plain words");
    if (!seen.insert(key.text()).second) context.fail(key, what_ + ": duplicate key " + quoted(key.text()));
  }
}

void MapReader::allowKeys(const std::vector<std::string>& keys) const {
  for (std::size_t i = 0; i < node_.size(); ++i) {
    const std::string& key = node_.key(i).text();
    if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
    context_.fail(node_.value(i), node_.key(i).mark(),
                  what_ + ": unknown key " + quoted(key) + suggestion(key, keys) +
                      "; allowed keys: " + listOf(keys));
  }
}

bool MapReader::has(const std::string& key) const { return node_[key].isDefined(); }

bool MapReader::inDegrees(const std::string& key) const {
  const YamlNode& value = node_[key];
  return value.isDefined() && value.isScalar() && writtenInDegrees(value.text());
}

const YamlNode& MapReader::required(const std::string& key) const {
  const YamlNode& value = node_[key];
  if (!value.isDefined()) context_.fail(node_, what_ + ": missing required key '" + key + "'");
  return value;
}

YamlMark MapReader::markOf(const std::string& key) const {
  const YamlNode& value = node_[key];
  return value.isDefined() && !value.mark().isNull() ? value.mark() : node_.mark();
}

void MapReader::fail(const std::string& key, const std::string& what) const {
  const YamlNode& value = node_[key];
  if (value.isDefined()) context_.fail(value, what_ + ": " + what);
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
  const YamlNode& value = required(key);
  if (!value.isSequence() || value.size() != 3)
    fail(key, key + ": expected a vector [x, y, z], got " +
                  (value.isSequence() ? "a list of " + std::to_string(value.size()) : describe(value)));
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = readNumber(context_, value[i], what_ + ": " + key);
  return v;
}

Eigen::Vector3d MapReader::vector(const std::string& key, const Eigen::Vector3d& fallback) const {
  return has(key) ? vector(key) : fallback;
}

std::string MapReader::name(const std::string& key) const {
  const YamlNode& value = required(key);
  if (!value.isScalar()) fail(key, key + ": expected a name, got " + describe(value));
  const std::string& text = value.text();
  const bool valid = !text.empty() && (std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_') &&
                     std::all_of(text.begin(), text.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  if (!valid) fail(key, key + ": " + quoted(text) + " is not a valid name (a letter or '_', then letters, digits, '_')");
  return text;
}

std::string MapReader::choice(const std::string& key, const std::vector<std::string>& choices,
                              const std::string& fallback) const {
  if (!has(key) && !fallback.empty()) return fallback;
  const YamlNode& value = required(key);
  if (value.isScalar())
    for (const std::string& choice : choices)
      if (value.text() == choice) return choice;
  fail(key, key + ": expected one of " + listOf(choices) + ", got " + describe(value));
}

std::vector<std::reference_wrapper<const YamlNode>> readList(const YamlContext& context, const YamlNode& node,
                                                             const std::string& what) {
  if (!node.isDefined() || node.isNull()) return {};
  if (!node.isSequence()) context.fail(node, what + ": expected a list of entries ('- ...'), got " + describe(node));
  std::vector<std::reference_wrapper<const YamlNode>> elements;
  for (std::size_t i = 0; i < node.size(); ++i) elements.emplace_back(node[i]);
  return elements;
}

}  // namespace mbsopt
