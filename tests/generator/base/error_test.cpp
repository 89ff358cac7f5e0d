// quoted() (generator/base/error.h), the one way a message shows a user's value, and the field
// paths of mapping keys (child_path, generator/io/yaml_reader.h): escaped, one line, short.
#include "base/error.h"

#include <gtest/gtest.h>

#include <string>

#include "io/yaml_reader.h"

namespace cutaway {
namespace {

/// Whether `s` has a byte a terminal would act on: C0 controls (newline included) and DEL.
bool has_raw_control(const std::string& s) {
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f) return true;
  return false;
}

TEST(Quoted, PlainTextInDoubleQuotes) {
  EXPECT_EQ(quoted("tomato"), "\"tomato\"");
  EXPECT_EQ(quoted(""), "\"\"");
  EXPECT_EQ(quoted(std::string("name ")), "\"name \"");
  EXPECT_EQ(quoted("café ☕"), "\"café ☕\"");  // printable UTF-8 stays as it is
}

TEST(Quoted, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(quoted("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(quoted("a\nb\tc\rd"), "\"a\\nb\\tc\\rd\"");
  EXPECT_EQ(quoted(std::string("f\x7frmat")), "\"f\\x7frmat\"");
  EXPECT_EQ(quoted(std::string("\x01\x1b[31m", 6)), "\"\\x01\\x1b[31m\"");
  EXPECT_EQ(quoted(std::string("a\0b", 3)), "\"a\\x00b\"");
  // C1 controls (U+0085 NEL), invisible format characters (U+202E right-to-left override,
  // U+2028 line separator, U+FEFF) and bytes that are not UTF-8.
  EXPECT_EQ(quoted("a\xc2\x85z"), "\"a\\xc2\\x85z\"");
  EXPECT_EQ(quoted("a\xe2\x80\xaez"), "\"a\\u202ez\"");
  EXPECT_EQ(quoted("a\xe2\x80\xa8z"), "\"a\\u2028z\"");
  EXPECT_EQ(quoted("\xef\xbb\xbfz"), "\"\\ufeffz\"");
  EXPECT_EQ(quoted("a\xff\xc3z"), "\"a\\xff\\xc3z\"");
  EXPECT_EQ(quoted("\xed\xa0\x80"), "\"\\xed\\xa0\\x80\"");  // a UTF-16 surrogate
}

TEST(Quoted, ElidesTheMiddleOfLongValues) {
  const std::string big = "abcd" + std::string(10u << 20, 'x') + "wxyz";
  const std::string q = quoted(big);
  EXPECT_LT(q.size(), 120u) << q;
  EXPECT_EQ(q.rfind("\"abcd", 0), 0u) << q;
  EXPECT_NE(q.find("(10485768 bytes)"), std::string::npos) << q;
  EXPECT_EQ(q.substr(q.size() - 5), "wxyz\"") << q;
  // A limit of its own; a value at the limit is whole.
  EXPECT_EQ(quoted(std::string(24, 'a'), 24), "\"aaaaaaaaaaaaaaaaaaaaaaaa\"");
  EXPECT_NE(quoted(std::string(25, 'a'), 24).find("(25 bytes)"), std::string::npos);
}

TEST(Quoted, LongValuesAreCutBetweenCharactersAndStayEscaped) {
  std::string big;
  for (int i = 0; i < 1000; ++i) big += "é\n";  // 3 bytes each
  const std::string q = quoted(big, 61);
  EXPECT_FALSE(has_raw_control(q)) << q;
  EXPECT_EQ(q.find("\\x"), std::string::npos) << "a character was split: " << q;
  EXPECT_LT(q.size(), 200u);
}

TEST(ChildPath, PlainKeysAreDottedOthersQuotedInBrackets) {
  EXPECT_EQ(child_path("(root)", "name"), "name");
  EXPECT_EQ(child_path("symmetry", "fold_angles"), "symmetry.fold_angles");
  EXPECT_EQ(child_path("surfaces[0]", "front-2"), "surfaces[0].front-2");
  EXPECT_EQ(child_path("symmetry", ""), "symmetry[\"\"]");
  EXPECT_EQ(child_path("symmetry", "name "), "symmetry[\"name \"]");
  EXPECT_EQ(child_path("(root)", "f\x7frmat"), "(root)[\"f\\x7frmat\"]");
  EXPECT_EQ(child_path("a", "b.c"), "a[\"b.c\"]");
  const std::string path = child_path("a", std::string(100000, 'k'));  // plain, but too long
  EXPECT_LT(path.size(), 120u) << path;
  EXPECT_TRUE(is_plain_key(std::string(kMaxPlainKeyLength, 'k')));
  EXPECT_FALSE(is_plain_key(std::string(kMaxPlainKeyLength + 1, 'k')));
}

TEST(YamlMessages, UnknownAndRepeatedKeysAreQuotedInPathAndRule) {
  auto message = [](const std::string& text) -> std::string {
    try {
      const YamlField root = parse_yaml(text, "t.yaml");
      root.require("symmetry").allow_only({"type", "folds"});
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message("symmetry:\n  type: none\n  \"\": 1\n"),
            "t.yaml:3:3: symmetry[\"\"]: unknown field \"\" (expected one of: type, folds)");
  EXPECT_EQ(message("symmetry: {type: none, \"a\\tb\": 1}\n"),
            "t.yaml:1:24: symmetry[\"a\\tb\"]: unknown field \"a\\tb\" (expected one of: type, "
            "folds)");
  EXPECT_EQ(message("symmetry: {type: none, type: x}\n"),
            "t.yaml:1:24: symmetry.type: field \"type\" is given twice");
}

TEST(YamlMessages, ValuesInTypeErrorsAreQuoted) {
  const YamlField root = parse_yaml("a: \"x\\ny\"\nb: \"#12\\u0007\"\n", "t.yaml");
  try {
    root.require("a").number();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "must be a number, not \"x\\ny\"");
  }
  try {
    parse_colour(root.require("b"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.rule().find("not \"#12\\x07\""), std::string::npos) << e.rule();
  }
}

}  // namespace
}  // namespace cutaway
