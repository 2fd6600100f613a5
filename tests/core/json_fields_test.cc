#include "slam/core/json_fields.h"

#include <functional>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(JsonFields, ReadsKnownKeysAndKeepsDefaults) {
  const auto json = nlohmann::json::parse(R"({"width": 320, "name": "x"})");
  JsonFields fields(json, "test.json");
  int width = 640;
  int height = 480;
  std::string name;
  fields.Read("width", &width);
  fields.Read("height", &height);
  fields.Read("name", &name);
  fields.RejectUnknown();
  EXPECT_EQ(width, 320);
  EXPECT_EQ(height, 480);
  EXPECT_EQ(name, "x");
}

TEST(JsonFields, RejectsUnknownKeyWithItsPath) {
  const auto json = nlohmann::json::parse(R"({"camera": {"widht": 320}})");
  JsonFields fields(json, "cfg.json");
  JsonFields camera = fields.Child("camera");
  int width = 0;
  camera.Read("width", &width);
  try {
    camera.RejectUnknown();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "cfg.json.camera: unknown key 'widht'");
  }
}

TEST(JsonFields, CommentKeyIsAllowedButItsMisspellingIsNot) {
  const auto json = nlohmann::json::parse(R"({"_comment": "why these values", "width": 1})");
  JsonFields fields(json, "cfg.json");
  int width = 0;
  fields.Read("width", &width);
  EXPECT_NO_THROW(fields.RejectUnknown());
  const auto typo = nlohmann::json::parse(R"({"_coment": "x"})");
  EXPECT_THROW(JsonFields(typo, "cfg.json").RejectUnknown(), ConfigError);
}

TEST(JsonFields, RejectsWrongType) {
  const auto json = nlohmann::json::parse(R"({"width": "wide"})");
  JsonFields fields(json, "cfg.json");
  int width = 0;
  EXPECT_THROW(fields.Read("width", &width), ConfigError);
}

TEST(ReadJsonFile, NamesFileOnBadInput) {
  try {
    ReadJsonFile("/nonexistent/file.json");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/file.json"), std::string::npos);
  }
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonFields, IntegersAreNeverTruncatedOrWrapped) {
  const auto json = nlohmann::json::parse(
      R"({"a": 4294967298, "b": 1.5, "c": 1e12, "d": -1, "e": 2.0, "f": 1e3, "g": [1, 2.5], "h": [30, 60]})");
  JsonFields fields(json, "cfg.json:matrix");
  int i = 0;
  EXPECT_NE(ErrorOf([&] { fields.Read("a", &i); })
                .find("cfg.json:matrix.a: 4294967298 is out of range (-2147483648 to 2147483647)"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { fields.Read("b", &i); }).find("cfg.json:matrix.b: expected an integer, got 1.5"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { fields.Read("c", &i); }).find("out of range"), std::string::npos);
  uint32_t u = 0;
  EXPECT_NE(ErrorOf([&] { fields.Read("d", &u); }).find("cfg.json:matrix.d: -1 is out of range"),
            std::string::npos);
  fields.Read("e", &i);
  EXPECT_EQ(i, 2);
  fields.Read("f", &i);
  EXPECT_EQ(i, 1000);
  int64_t big = 0;
  fields.Read("a", &big);
  EXPECT_EQ(big, 4294967298LL);
  std::vector<int> list;
  EXPECT_NE(ErrorOf([&] { fields.Read("g", &list); }).find("cfg.json:matrix.g[1]: expected an integer"),
            std::string::npos);
  fields.Read("h", &list);
  EXPECT_EQ(list, (std::vector<int>{30, 60}));
}

TEST(ParseJsonText, DuplicateKeysAreErrorsWithTheirPath) {
  EXPECT_NE(ErrorOf([] { ParseJsonText(R"({"frame_step": 1, "frame_step": 2})", "c.json"); })
                .find("c.json: key 'frame_step' is given twice"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] {
              ParseJsonText(R"({"dataset": {"path": "a", "path": "b"}})", "c.json");
            }).find("key 'dataset.path' is given twice"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] {
              ParseJsonText(R"({"sessions": [{"name": "1"}, {"name": "2", "name": "3"}]})", "c.json");
            }).find("key 'sessions[].name' is given twice"),
            std::string::npos);
  // The same key in two objects is fine.
  EXPECT_NO_THROW(ParseJsonText(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 1}, {"x": 2}]})", "c.json"));
}

TEST(ParseJsonText, InvalidJsonNamesLineAndColumn) {
  const std::string message = ErrorOf([] { ParseJsonText("{\n  \"a\": 1,\n  \"b\" 2\n}", "c.json"); });
  EXPECT_EQ(message.rfind("c.json:3:", 0), 0u) << message;
  EXPECT_NE(message.find("invalid JSON ("), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace duskmap
