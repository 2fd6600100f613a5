#include "slam/core/json_fields.h"

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

}  // namespace
}  // namespace duskmap
