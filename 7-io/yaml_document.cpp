#include "mbsopt/io/yaml_document.hpp"

#include <yaml.h>

#include <algorithm>
#include <array>
#include <map>
#include <optional>

namespace mbsopt {

const YamlNode& YamlNode::undefined() {
  static const YamlNode node;
  return node;
}

const YamlNode& YamlNode::operator[](std::size_t index) const {
  return isSequence() && index < children_.size() ? *children_[index] : undefined();
}

const YamlNode& YamlNode::operator[](std::string_view key) const {
  const YamlNode* found = const_cast<YamlNode*>(this)->find(key);
  return found != nullptr ? *found : undefined();
}

YamlNode* YamlNode::find(std::string_view key) {
  if (!isMap()) return nullptr;
  for (std::size_t i = 0; i < children_.size(); i += 2)
    if (children_[i]->isScalar() && children_[i]->text() == key) return children_[i + 1].get();
  return nullptr;
}

YamlNode& YamlNode::append(YamlNode element) {
  children_.push_back(std::make_unique<YamlNode>(std::move(element)));
  return *children_.back();
}

YamlNode& YamlNode::insert(YamlNode key, YamlNode value) {
  children_.push_back(std::make_unique<YamlNode>(std::move(key)));
  children_.push_back(std::make_unique<YamlNode>(std::move(value)));
  return *children_.back();
}

void YamlNode::assign(std::string text) {
  kind_ = Kind::Scalar;
  text_ = std::move(text);
  children_.clear();
}

namespace {

YamlMark markOf(const yaml_mark_t& mark) { return {static_cast<int>(mark.line), static_cast<int>(mark.column)}; }

/// Line and column of byte `offset` (libyaml's reader errors give an offset only).
YamlMark markAtOffset(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const std::string_view before = text.substr(0, offset);
  const std::size_t line_start = before.rfind('\n');
  const auto line = static_cast<int>(std::count(before.begin(), before.end(), '\n'));
  return {line, static_cast<int>(line_start == std::string_view::npos ? offset : offset - line_start - 1)};
}

/// The YAML core schema's nulls, as plain scalars.
bool isPlainNull(std::string_view text) {
  constexpr std::array<std::string_view, 5> nulls{"", "~", "null", "Null", "NULL"};
  return std::find(nulls.begin(), nulls.end(), text) != nulls.end();
}

class Parser {
 public:
  Parser(std::string_view text, const YamlLimits& limits) : text_(text), limits_(limits) {
    if (yaml_parser_initialize(&parser_) == 0) throw YamlSyntaxError("out of memory while starting the YAML parser", {});
    yaml_parser_set_input_string(&parser_, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  }
  ~Parser() { yaml_parser_delete(&parser_); }
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;

  YamlNode run() {
    for (bool done = false; !done;) {
      Event event(parser_);
      if (!event.parsed) failParse();
      done = handle(event.event);
    }
    return std::move(root_);
  }

 private:
  /// One event, released at the end of its scope.
  struct Event {
    explicit Event(yaml_parser_t& parser) : parsed(yaml_parser_parse(&parser, &event) != 0) {}
    ~Event() {
      if (parsed) yaml_event_delete(&event);
    }
    Event(const Event&) = delete;
    Event& operator=(const Event&) = delete;
    yaml_event_t event{};
    bool parsed;
  };

  /// An open sequence or map, and for a map the key that waits for its value.
  struct Open {
    YamlNode* node;
    std::unique_ptr<YamlNode> pending_key;
  };

  [[noreturn]] void failParse() const {
    const std::string problem =
        std::string("malformed YAML: ") + (parser_.problem != nullptr ? parser_.problem : "unknown error");
    switch (parser_.error) {
      case YAML_MEMORY_ERROR:
        throw YamlSyntaxError("out of memory while parsing", {});
      case YAML_READER_ERROR:
        throw YamlSyntaxError(problem, markAtOffset(text_, parser_.problem_offset));
      default:
        throw YamlSyntaxError(problem, markOf(parser_.problem_mark), parser_.context != nullptr ? parser_.context : "",
                              markOf(parser_.context_mark));
    }
  }

  /// Handles one event; true at the end of the stream.
  bool handle(const yaml_event_t& event) {
    const YamlMark mark = markOf(event.start_mark);
    switch (event.type) {
      case YAML_STREAM_END_EVENT:
        return true;
      case YAML_DOCUMENT_START_EVENT:
        if (++documents_ > 1)
          throw YamlSyntaxError("the file holds more than one YAML document ('---'); a scene is one document", mark);
        return false;
      case YAML_ALIAS_EVENT:
        alias(reinterpret_cast<const char*>(event.data.alias.anchor), mark);
      case YAML_SCALAR_EVENT: {
        const auto& scalar = event.data.scalar;
        checkTag(scalar.tag, mark);
        std::string text(reinterpret_cast<const char*>(scalar.value), scalar.length);
        const bool null = scalar.style == YAML_PLAIN_SCALAR_STYLE && isPlainNull(text);
        add(YamlNode(null ? YamlNode::Kind::Null : YamlNode::Kind::Scalar, mark, null ? "" : std::move(text)),
            scalar.anchor, mark);
        return false;
      }
      case YAML_SEQUENCE_START_EVENT:
        checkTag(event.data.sequence_start.tag, mark);
        open(add(YamlNode(YamlNode::Kind::Sequence, mark), event.data.sequence_start.anchor, mark), mark);
        return false;
      case YAML_MAPPING_START_EVENT:
        checkTag(event.data.mapping_start.tag, mark);
        open(add(YamlNode(YamlNode::Kind::Map, mark), event.data.mapping_start.anchor, mark), mark);
        return false;
      case YAML_SEQUENCE_END_EVENT:
      case YAML_MAPPING_END_EVENT:
        open_.pop_back();
        return false;
      default:  // stream start, document end, nothing to build
        return false;
    }
  }

  static void checkTag(const yaml_char_t* tag, const YamlMark& mark) {
    if (tag != nullptr)
      throw YamlSyntaxError("tags ('!!str', '!name') are not part of a scene file: write the value alone", mark);
  }

  /// A node reachable by two paths would have two dotted names: aliases are refused.
  [[noreturn]] void alias(const char* name, const YamlMark& mark) const {
    const auto anchor = anchors_.find(name);
    if (anchor == anchors_.end())
      throw YamlSyntaxError("the alias '*" + std::string(name) + "' names no anchor ('&" + name + "')", mark);
    throw YamlSyntaxError("this value is anchored ('&" + std::string(name) + "') and reused by an alias ('*" + name +
                              "', line " + std::to_string(mark.line + 1) +
                              "); a scene refuses aliases, so that every number has one name of its own",
                          anchor->second);
  }

  /// Places `node` in the open container (or as the root); returns it in the tree.
  YamlNode& add(YamlNode node, const yaml_char_t* anchor, const YamlMark& mark) {
    if (anchor != nullptr) anchors_.emplace(reinterpret_cast<const char*>(anchor), mark);
    if (open_.empty()) {
      root_ = std::move(node);
      return root_;
    }
    Open& parent = open_.back();
    if (parent.node->isSequence()) return parent.node->append(std::move(node));
    if (!parent.pending_key) {
      parent.pending_key = std::make_unique<YamlNode>(std::move(node));
      return *parent.pending_key;
    }
    // A key that is itself a list or map was filled in place: its END came before this value.
    YamlNode& value = parent.node->insert(std::move(*parent.pending_key), std::move(node));
    parent.pending_key.reset();
    return value;
  }

  void open(YamlNode& node, const YamlMark& mark) {
    if (static_cast<int>(open_.size()) >= limits_.max_depth)
      throw YamlSyntaxError("lists and maps nested more than " + std::to_string(limits_.max_depth) + " levels deep",
                            mark);
    open_.push_back({&node, nullptr});
  }

  std::string_view text_;
  const YamlLimits& limits_;
  yaml_parser_t parser_{};
  YamlNode root_;
  std::vector<Open> open_;
  std::map<std::string, YamlMark, std::less<>> anchors_;
  int documents_ = 0;
};

}  // namespace

YamlNode parseYamlDocument(std::string_view text, const YamlLimits& limits) {
  if (text.size() > limits.max_bytes)
    throw YamlSyntaxError("the file has " + std::to_string(text.size()) + " bytes, more than the limit of " +
                              std::to_string(limits.max_bytes) + " bytes",
                          {});
  return Parser(text, limits).run();
}

}  // namespace mbsopt
