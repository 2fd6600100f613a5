#include "slam/synthetic/assets/java_properties.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(ParseJavaProperties, ReadsSeparatorsCommentsAndBlanks) {
  const auto p = ParseJavaProperties(
      "# comment\n! another\n\n  a=1\nb = two words \nc:3\nd 4\ne\nf==x\n g\t:\t y\n", "test.properties");
  EXPECT_EQ(p.at("a"), "1");
  EXPECT_EQ(p.at("b"), "two words ");  // trailing blanks are part of the value
  EXPECT_EQ(p.at("c"), "3");
  EXPECT_EQ(p.at("d"), "4");
  EXPECT_EQ(p.at("e"), "");
  EXPECT_EQ(p.at("f"), "=x");
  EXPECT_EQ(p.at("g"), "y");
  EXPECT_EQ(p.size(), 7u);
}

TEST(ParseJavaProperties, ResolvesEscapesAndContinuations) {
  const auto p = ParseJavaProperties(
      "name#1=Caf\\u00e9 cr\\u00e8me\n"
      "key\\:with\\=seps=v\\:1\n"
      "long=first \\\n    second \\\r\n\tthird\n"
      "tab=a\\tb\\nc\n"
      "backslash=ends\\\\\n"
      "next=after\n"
      "emoji=\\uD83D\\uDE00\n"
      "# a comment ending in a backslash does not continue \\\n"
      "kept=yes\r"
      "crlf=1\r\n",
      "test.properties");
  EXPECT_EQ(p.at("name#1"), "Caf\xC3\xA9 cr\xC3\xA8me");
  EXPECT_EQ(p.at("key:with=seps"), "v:1");
  EXPECT_EQ(p.at("long"), "first second third");
  EXPECT_EQ(p.at("tab"), "a\tb\nc");
  EXPECT_EQ(p.at("backslash"), "ends\\");
  EXPECT_EQ(p.at("next"), "after");
  EXPECT_EQ(p.at("emoji"), "\xF0\x9F\x98\x80");
  EXPECT_EQ(p.at("kept"), "yes");
  EXPECT_EQ(p.at("crlf"), "1");
}

TEST(ParseJavaProperties, ReadsLatin1WhenNotUtf8AndKeepsUtf8) {
  EXPECT_EQ(ParseJavaProperties("n=Caf\xE9\n", "x").at("n"), "Caf\xC3\xA9");
  EXPECT_EQ(ParseJavaProperties("n=Caf\xC3\xA9\n", "x").at("n"), "Caf\xC3\xA9");
}

TEST(ParseJavaProperties, TheLastOfARepeatedKeyWins) {
  EXPECT_EQ(ParseJavaProperties("a=1\na=2\n", "x").at("a"), "2");
}

TEST(ParseJavaProperties, AMalformedUnicodeEscapeNamesTheFileAndLine) {
  try {
    ParseJavaProperties("a=1\n\nb=\\u12G4\n", "cat.sh3f!/PluginFurnitureCatalog.properties");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "cat.sh3f!/PluginFurnitureCatalog.properties:3: malformed \\uXXXX escape");
  }
}

}  // namespace
}  // namespace duskmap
