// Typed, located reading of a YAML scene: numbers (with an optional `deg` suffix), vectors, names
// and choices, with unknown, duplicate and missing keys reported at their line and column.
#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "mbsopt/io/yaml_document.hpp"

#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {

/// The file being read, and the nodes that `--set` overrode (named in the errors they cause).
class YamlContext {
 public:
  explicit YamlContext(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }
  [[noreturn]] void fail(const YamlNode& node, const std::string& what) const;
  [[noreturn]] void fail(const YamlMark& mark, const std::string& what) const;
  /// At `mark`, naming the overrides inside `node`.
  [[noreturn]] void fail(const YamlNode& node, const YamlMark& mark, const std::string& what) const;
  void markOverridden(const YamlNode& node, std::string origin);

 private:
  std::string path_;
  std::vector<std::pair<const YamlNode*, std::string>> overridden_;
};

/// A number node: finite, else an error at the node.
double readNumber(const YamlContext& context, const YamlNode& node, const std::string& what);

/// Reads one YAML map, checking its keys: allowed ones only, no duplicates, required ones present.
class MapReader {
 public:
  /// `what` names the map in messages ("body 'bob'", "settings").
  MapReader(const YamlContext& context, const YamlNode& node, std::string what);

  /// Declares the allowed keys and reports the first one that is not, with a suggestion.
  void allowKeys(const std::vector<std::string>& keys) const;

  bool has(const std::string& key) const;
  /// Whether the key's value is a number written with the `deg` suffix.
  bool inDegrees(const std::string& key) const;
  const YamlNode& node() const { return node_; }
  const std::string& what() const { return what_; }
  const YamlContext& context() const { return context_; }
  /// The value of a key that must be present.
  const YamlNode& required(const std::string& key) const;
  /// The location of a key (its value if present, else the map).
  YamlMark markOf(const std::string& key) const;

  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  double positive(const std::string& key) const;
  double nonNegative(const std::string& key, double fallback) const;
  int positiveInteger(const std::string& key, int fallback) const;
  Eigen::Vector3d vector(const std::string& key) const;
  Eigen::Vector3d vector(const std::string& key, const Eigen::Vector3d& fallback) const;
  /// A name: letters, digits and '_', starting with a letter or '_'.
  std::string name(const std::string& key) const;
  /// One of `choices`; `fallback` when absent (empty: required).
  std::string choice(const std::string& key, const std::vector<std::string>& choices,
                     const std::string& fallback = "") const;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  const YamlContext& context_;
  const YamlNode& node_;
  std::string what_;
};

/// Reads a YAML sequence (an absent node reads as empty); anything else is an error.
std::vector<std::reference_wrapper<const YamlNode>> readList(const YamlContext& context, const YamlNode& node, const std::string& what);

}  // namespace mbsopt
