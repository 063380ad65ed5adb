// core/text.h: names are data, never code (issue 28).
#include <gtest/gtest.h>

#include "catalog/material.h"
#include "core/text.h"
#include "targets/writer.h"

namespace facet {
namespace {

TEST(Text, LineBreaksAreFoundByCharacterNotByte) {
  EXPECT_FALSE(line_break("Gold \"polished\" */ # \\ — ünïcödé ✓"));
  auto b = line_break("ü\nx");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->at, 1u);
  EXPECT_EQ(b->code, U'\n');
  EXPECT_EQ(describe(*b), "contains U+000A (a line feed) at character 1");
  for (const char* s : {"a\rb", "a\0b", "a\x1b[31mb", "a\x7f", "a\xc2\x85", "a\xe2\x80\xa8", "a\xe2\x80\xa9"}) {
    const std::string text(s, std::string_view(s).size() + (s[1] == '\0' ? 2 : 0));
    EXPECT_TRUE(line_break(text)) << text;
  }
  EXPECT_EQ(line_break("a\xe2\x80\xa8")->code, U'\u2028');
}

TEST(Text, OneLineShowsEachBreakAsAStandIn) {
  EXPECT_EQ(one_line("x\n#error\r\x1b"), "x\xE2\x90\x8A#error\xE2\x90\x8D\xE2\x90\x9B");  // ␊ ␍ ␛
  EXPECT_EQ(one_line("a\x7f" "b\xe2\x80\xa8" "c"), "a\xE2\x90\xA1" "b\xE2\x90\xA4" "c");  // ␡ ␤
  EXPECT_EQ(one_line("ünïcödé \"q\" \\"), "ünïcödé \"q\" \\");                          // the rest kept
  EXPECT_FALSE(line_break(one_line(std::string("a\0\n\r\t\x85", 6))));
}

TEST(Text, QuotedLiteralsEscapeQuoteAndBackslash) {
  EXPECT_EQ(quoted_literal("a\"b\\c.png"), "\"a\\\"b\\\\c.png\"");
  EXPECT_EQ(quoted_literal("plain/path.png"), "\"plain/path.png\"");
}

TEST(Text, LongIdentifiersKeepTheirStartAndAHashOfTheWhole) {
  const std::string a(10000, 'n'), b = a + "x";
  EXPECT_EQ(identifier(a).size(), kIdentifierMax);
  EXPECT_EQ(identifier(a).substr(0, 40), std::string(40, 'n'));
  EXPECT_NE(identifier(a), identifier(b));   // the hash tells them apart
  EXPECT_EQ(identifier(a), identifier(a));   // and is the same every run
  EXPECT_EQ(identifier("gold 2"), "gold_2");  // short names as ever
}

// A C preprocessor (GLSL, HLSL, OSL) splices the line after a backslash-ended line into a
// // comment: a name's backslash never ends a comment line, where the words wrap or not.
TEST(Text, NoCommentLineEndsInABackslash) {
  const std::string name = "object \"a \\ b\" " + std::string(60, 'x') + " and more words after it";
  for (size_t width : {0, 20, 40, 50, 80}) {
    std::string out;
    targets::comment_to(out, name, "  ", "//", width);
    targets::comment_to(out, "ends in \\", "", "//", width);
    for (size_t end = out.find('\n'); end != std::string::npos; end = out.find('\n', end + 1))
      EXPECT_NE(out[end - 1], '\\') << "width " << width << ":\n" << out;
    EXPECT_NE(out.find("\\ b"), std::string::npos) << out;  // the name's backslash is still there
    EXPECT_NE(out.find("ends in \\·"), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace facet
