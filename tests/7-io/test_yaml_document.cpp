// The YAML front end (7-io/yaml_document.hpp): the tree and its positions, the YAML core
// schema's nulls, what a scene refuses (aliases, tags, a second document) and the limits on size
// and nesting. Positions are read off the literal texts below (0-based line and column).
#include <gtest/gtest.h>

#include <string>

#include "mbsopt/io/yaml_document.hpp"

namespace mbsopt {
namespace {

/// The error `text` raises; fails the test when it parses.
YamlSyntaxError errorOf(const std::string& text, const YamlLimits& limits = kYamlLimits) {
  try {
    parseYamlDocument(text, limits);
  } catch (const YamlSyntaxError& e) {
    return e;
  }
  ADD_FAILURE() << "parsed without error: " << text;
  return YamlSyntaxError("", {});
}

std::string nested(int depth) { return std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']'); }

TEST(YamlDocument, TreeAndPositions) {
  const YamlNode root = parseYamlDocument(
      "a: 1\n"                 // line 0
      "b:\n"                   // line 1
      "  - x\n"                // line 2
      "  - {c: [1, 2, 3]}\n");  // line 3
  ASSERT_TRUE(root.isMap());
  ASSERT_EQ(root.size(), 2u);
  EXPECT_EQ(root.key(0).text(), "a");
  EXPECT_EQ(root["a"].text(), "1");
  EXPECT_EQ(root["a"].mark().line, 0);
  EXPECT_EQ(root["a"].mark().column, 3);
  const YamlNode& b = root["b"];
  ASSERT_TRUE(b.isSequence());
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0].text(), "x");
  EXPECT_EQ(b[0].mark().line, 2);
  EXPECT_EQ(b[0].mark().column, 4);
  const YamlNode& c = b[1]["c"];
  ASSERT_TRUE(c.isSequence());
  EXPECT_EQ(c.size(), 3u);
  EXPECT_EQ(c[2].text(), "3");
  EXPECT_EQ(c[2].mark().line, 3);
  EXPECT_EQ(c[2].mark().column, 15);
  EXPECT_FALSE(root["missing"].isDefined());
  EXPECT_FALSE(b[7].isDefined());
  EXPECT_FALSE(root["a"]["not a map"].isDefined());
}

TEST(YamlDocument, CoreSchemaNullsArePlainOnly) {
  const YamlNode root = parseYamlDocument("a: ~\nb:\nc: null\nd: NULL\ne: \"null\"\nf: ''\ng: nil\n");
  for (const char* key : {"a", "b", "c", "d"}) EXPECT_TRUE(root[key].isNull()) << key;
  for (const char* key : {"e", "f", "g"}) EXPECT_TRUE(root[key].isScalar()) << key;
  EXPECT_EQ(root["e"].text(), "null");
  EXPECT_EQ(root["f"].text(), "");
}

TEST(YamlDocument, DuplicateKeysAreKeptInOrder) {
  const YamlNode root = parseYamlDocument("k: 1\nk: 2\n");
  ASSERT_EQ(root.size(), 2u);
  EXPECT_EQ(root["k"].text(), "1");  // the first: the loader reports the duplicate at the second
  EXPECT_EQ(root.value(1).text(), "2");
  EXPECT_EQ(root.key(1).mark().line, 1);
}

TEST(YamlDocument, AComplexKeyIsANodeOfItsOwn) {
  const YamlNode root = parseYamlDocument("? [a, b]\n: 1\n");
  ASSERT_EQ(root.size(), 1u);
  EXPECT_TRUE(root.key(0).isSequence());
  EXPECT_EQ(root.key(0)[1].text(), "b");
  EXPECT_EQ(root.value(0).text(), "1");
}

TEST(YamlDocument, InsertedNodesKeepEarlierReferencesValid) {
  YamlNode root = parseYamlDocument("a: 1\n");
  const YamlNode& a = root["a"];
  for (int i = 0; i < 100; ++i) root.insert({YamlNode::Kind::Scalar, {}, "k" + std::to_string(i)}, {YamlNode::Kind::Map, {}});
  EXPECT_EQ(&root["a"], &a);
  EXPECT_EQ(a.text(), "1");
  EXPECT_TRUE(root["k99"].isMap());
  EXPECT_TRUE(root["k99"].mark().isNull());
}

TEST(YamlDocument, NoDocumentIsUndefined) {
  EXPECT_FALSE(parseYamlDocument("").isDefined());
  EXPECT_FALSE(parseYamlDocument("# only a comment\n").isDefined());
}

// The input that made yaml-cpp 0.7 loop forever (jbeder/yaml-cpp#1040): a located syntax error.
TEST(YamlDocument, LeadingCommaIsASyntaxError) {
  const YamlSyntaxError e = errorOf(",a: 1\n");
  EXPECT_NE(std::string(e.what()).find("malformed YAML"), std::string::npos) << e.what();
  EXPECT_EQ(e.mark().line, 0);
}

TEST(YamlDocument, UnclosedFlowNamesWhereItOpened) {
  const YamlSyntaxError e = errorOf("a: [1, 2\nb: 3\n");
  EXPECT_NE(std::string(e.what()).find("']'"), std::string::npos) << e.what();
  EXPECT_EQ(e.contextMark().line, 0);
  EXPECT_EQ(e.contextMark().column, 3);
}

TEST(YamlDocument, AliasIsRefusedAtItsAnchor) {
  const YamlSyntaxError e = errorOf("a: &z [0, 0, 1]\nb: *z\n");
  EXPECT_NE(std::string(e.what()).find("alias ('*z', line 2)"), std::string::npos) << e.what();
  EXPECT_EQ(e.mark().line, 0);
  EXPECT_EQ(e.mark().column, 3);
  EXPECT_NE(std::string(errorOf("b: *nowhere\n").what()).find("names no anchor"), std::string::npos);
}

TEST(YamlDocument, TagIsRefused) {
  const YamlSyntaxError e = errorOf("a: !!str 5\n");
  EXPECT_NE(std::string(e.what()).find("tags"), std::string::npos) << e.what();
  EXPECT_EQ(e.mark().line, 0);
}

TEST(YamlDocument, SecondDocumentIsRefusedAtItsStart) {
  const YamlSyntaxError e = errorOf("a: 1\n---\nb: 2\n");
  EXPECT_NE(std::string(e.what()).find("more than one YAML document"), std::string::npos) << e.what();
  EXPECT_EQ(e.mark().line, 1);
}

// Two-sided: the limit itself is accepted, one more is refused, at the bracket that exceeds it.
TEST(YamlDocument, NestingLimitIsExact) {
  const YamlLimits limits{1 << 20, 8};
  EXPECT_TRUE(parseYamlDocument(nested(8), limits).isSequence());
  const YamlSyntaxError e = errorOf(nested(9), limits);
  EXPECT_NE(std::string(e.what()).find("nested more than 8 levels"), std::string::npos) << e.what();
  EXPECT_EQ(e.mark().column, 8);
  EXPECT_TRUE(parseYamlDocument(nested(kYamlLimits.max_depth)).isSequence());
  errorOf(nested(kYamlLimits.max_depth + 1));
}

TEST(YamlDocument, SizeLimitIsExact) {
  const YamlLimits limits{10, 64};
  EXPECT_TRUE(parseYamlDocument("a: 123456", limits).isMap());  // 9 bytes
  EXPECT_TRUE(parseYamlDocument("a: 1234567", limits).isMap());  // 10
  const YamlSyntaxError e = errorOf("a: 12345678", limits);      // 11
  EXPECT_NE(std::string(e.what()).find("11 bytes, more than the limit of 10"), std::string::npos) << e.what();
  EXPECT_TRUE(e.mark().isNull());
}

// A million nested brackets stop at the depth limit: the parse ends without building them.
TEST(YamlDocument, DeepNestingStopsAtTheLimit) {
  const YamlSyntaxError e = errorOf(std::string(1'000'000, '['));
  EXPECT_NE(std::string(e.what()).find("nested more than"), std::string::npos) << e.what();
}

TEST(YamlDocument, InvalidUtf8IsLocated) {
  const YamlSyntaxError e = errorOf("a: 1\nb: \xff\xfe\n");
  EXPECT_NE(std::string(e.what()).find("malformed YAML"), std::string::npos) << e.what();
  EXPECT_EQ(e.mark().line, 1);
}

}  // namespace
}  // namespace mbsopt
