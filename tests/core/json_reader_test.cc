#include "slam/core/json_reader.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

std::string Nested(int levels, const std::string& open, const std::string& close,
                   const std::string& inner = "1") {
  std::string text;
  for (int i = 0; i < levels; ++i) text += open;
  text += inner;
  for (int i = 0; i < levels; ++i) text += close;
  return text;
}

// '[' * 200000 overflowed the stack (nlohmann's copy and dump() recurse once
// per level); refused while parsing, one line naming the file.
TEST(ParseJsonText, NestingDeeperThanTheLimitIsRefusedWhileParsing) {
  const std::string expected = "c.json: arrays and objects nested deeper than 64 levels";
  EXPECT_EQ(ErrorOf([] { ParseJsonText(std::string(200000, '['), "c.json"); }), expected);
  EXPECT_EQ(ErrorOf([] {
              ParseJsonText(std::string(200000, '[') + std::string(200000, ']'), "c.json");
            }),
            expected);
  std::string objects;
  for (int i = 0; i < 100000; ++i) objects += "{\"a\":";
  EXPECT_EQ(ErrorOf([&] { ParseJsonText(objects, "c.json"); }), expected);
  EXPECT_EQ(ErrorOf([] { ParseJsonText(Nested(65, "[", "]"), "c.json"); }), expected);
  EXPECT_EQ(ErrorOf([] { ParseJsonText("{\"x\": " + Nested(64, "[", "]") + "}", "c.json"); }),
            expected);
  // 64 levels are read, and what is read can be copied and written again.
  const nlohmann::json deepest = ParseJsonText(Nested(64, "{\"k\": ", "}"), "c.json");
  const nlohmann::json copy = deepest;
  EXPECT_EQ(ParseJsonText(copy.dump(), "again"), deepest);
  EXPECT_NO_THROW(ParseJsonText(Nested(63, "[", "]", "{}"), "c.json"));
}

TEST(ParseJsonText, NumbersBeyondDoublesRangeAreNamedByTheirKeyPath) {
  EXPECT_EQ(ErrorOf([] { ParseJsonText(R"({"matrix": {"foo": 1e400}})", "config.json"); }),
            "config.json: matrix.foo: number out of range (1e400)");
  EXPECT_EQ(ErrorOf([] {
              ParseJsonText(R"({"features": [{"a": 1}, {"b": [0, -2E+999]}]})", "config.json");
            }),
            "config.json: features[1].b[1]: number out of range (-2E+999)");
  EXPECT_EQ(ErrorOf([] { ParseJsonText("1e400", "n.json"); }),
            "n.json: number out of range (1e400)");
  // A value after a nested object in the same array is counted right.
  EXPECT_EQ(ErrorOf([] { ParseJsonText(R"([[1, 2], {"a": [3]}, 7, 1e309])", "n.json"); }),
            "n.json: [3]: number out of range (1e309)");
  // Underflow is zero, not an error; integers beyond 64 bits become doubles.
  EXPECT_EQ(ParseJsonText(R"({"a": 1e-400})", "n.json").at("a").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(ParseJsonText(R"({"a": 123456789012345678901234567890})", "n.json")
                       .at("a")
                       .get<double>(),
                   1.2345678901234568e29);
}

TEST(ParseJsonText, DuplicateKeysAreNamedWithTheirPathAfterArrays) {
  EXPECT_EQ(ErrorOf([] {
              ParseJsonText(R"({"s": [{"n": 1}, [], {"n": 2, "x": {"k": 1, "k": 2}}]})", "c.json");
            }),
            "c.json: key 's[].x.k' is given twice");
}

TEST(ReadJsonFile, NamesTheFileForEveryProblem) {
  const std::string path = testing::ProcessTempPath("deep.json");
  std::ofstream(path) << std::string(200000, '[');
  EXPECT_EQ(ErrorOf([&] { ReadJsonFile(path); }),
            path + ": arrays and objects nested deeper than 64 levels");
  std::ofstream(path) << "{\n  \"a\": 1e400\n}\n";
  EXPECT_EQ(ErrorOf([&] { ReadJsonFile(path); }), path + ": a: number out of range (1e400)");
  std::ofstream(path) << "{\"a\": [1, 2]}";
  EXPECT_EQ(ReadJsonFile(path).at("a").size(), 2u);
  const std::string missing = testing::ProcessTempPath("missing.json");
  EXPECT_EQ(ErrorOf([&] { ReadJsonFile(missing); }), missing + ": cannot open file");
}

}  // namespace
}  // namespace duskmap
