// A YAML document as a tree of located nodes, read by libyaml (the C reference parser, fuzzed
// continuously upstream), with limits on size and nesting that every input meets before it can
// cost more than time and memory proportional to its length (problems/scenes/README.md, "Limits").
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mbsopt {

/// Where a node starts: 0-based line and column (in characters); line < 0 for a node that no text
/// holds (one written by `--set`).
struct YamlMark {
  int line = -1;
  int column = -1;
  bool isNull() const { return line < 0; }
};

/// The limits every parse enforces.
struct YamlLimits {
  std::size_t max_bytes = std::size_t{16} << 20;  ///< 16 MiB
  int max_depth = 64;                             ///< nested sequences and maps
};
inline constexpr YamlLimits kYamlLimits{};

/// A text that is not one well-formed YAML document within the limits. `mark` is where the
/// problem is; `context` (may be empty) the construct it interrupted, at `context_mark`.
class YamlSyntaxError : public std::runtime_error {
 public:
  YamlSyntaxError(const std::string& problem, YamlMark mark, std::string context = {}, YamlMark context_mark = {})
      : std::runtime_error(problem), mark_(mark), context_(std::move(context)), context_mark_(context_mark) {}
  const YamlMark& mark() const { return mark_; }
  const std::string& context() const { return context_; }
  const YamlMark& contextMark() const { return context_mark_; }

 private:
  YamlMark mark_;
  std::string context_;
  YamlMark context_mark_;
};

/// One node: undefined (what a lookup of a missing key returns), null (`~`, `null`, nothing), a
/// scalar (its text), a sequence or a map (keys and values in file order, duplicates kept). Nodes
/// own their children; references to them stay valid while the tree lives, also across insertions.
class YamlNode {
 public:
  enum class Kind { Undefined, Null, Scalar, Sequence, Map };

  YamlNode() = default;
  YamlNode(Kind kind, YamlMark mark, std::string text = {}) : kind_(kind), mark_(mark), text_(std::move(text)) {}
  YamlNode(YamlNode&&) = default;
  YamlNode& operator=(YamlNode&&) = default;
  YamlNode(const YamlNode&) = delete;
  YamlNode& operator=(const YamlNode&) = delete;

  Kind kind() const { return kind_; }
  bool isDefined() const { return kind_ != Kind::Undefined; }
  bool isNull() const { return kind_ == Kind::Null; }
  bool isScalar() const { return kind_ == Kind::Scalar; }
  bool isSequence() const { return kind_ == Kind::Sequence; }
  bool isMap() const { return kind_ == Kind::Map; }
  const YamlMark& mark() const { return mark_; }
  /// The text of a scalar (empty for other kinds).
  const std::string& text() const { return text_; }

  /// Elements of a sequence, entries of a map; 0 for other kinds.
  std::size_t size() const { return isMap() ? children_.size() / 2 : children_.size(); }
  /// Element `index` of a sequence; the undefined node when there is none.
  const YamlNode& operator[](std::size_t index) const;
  /// The value of the first entry whose key is the scalar `key`; the undefined node when none.
  const YamlNode& operator[](std::string_view key) const;
  YamlNode* find(std::string_view key);
  /// Key and value of map entry `index` (< size()).
  const YamlNode& key(std::size_t index) const { return *children_[2 * index]; }
  const YamlNode& value(std::size_t index) const { return *children_[2 * index + 1]; }
  YamlNode& element(std::size_t index) { return *children_[index]; }

  /// Appends to a sequence; returns the element in the tree.
  YamlNode& append(YamlNode element);
  /// Appends an entry to a map; returns the value in the tree.
  YamlNode& insert(YamlNode key, YamlNode value);
  /// Turns the node into the scalar `text`, keeping its place in the file.
  void assign(std::string text);

  /// The node every failed lookup returns.
  static const YamlNode& undefined();

 private:
  Kind kind_ = Kind::Undefined;
  YamlMark mark_;
  std::string text_;
  std::vector<std::unique_ptr<YamlNode>> children_;  ///< elements, or key and value alternately
};

/// Parses `text` as one YAML document. A text without a document gives an undefined node. Throws
/// YamlSyntaxError on malformed YAML, on more than one document, on an anchor reused by an alias
/// (a reused value would have two names), on a tag, and beyond `limits`.
YamlNode parseYamlDocument(std::string_view text, const YamlLimits& limits = kYamlLimits);

}  // namespace mbsopt
