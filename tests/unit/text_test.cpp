// core/text.h: names are data, never code (issue 28).
#include <gtest/gtest.h>

#include "catalog/material.h"
#include "core/text.h"

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

}  // namespace
}  // namespace facet
