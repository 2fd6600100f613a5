#include "slam/retrieval/lcd_options_json.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(LcdOptionsJson, ReadsNestedFieldsAndKeepsDefaults) {
  const auto json = nlohmann::json::parse(R"({
    "vocabulary": {"nndr_ratio": 0.7, "index": {"binary_kind": "lsh", "checks": 64}},
    "bayes": {"virtual_place_prior": 0.8},
    "loop_threshold": 0.2})");
  const LoopClosureOptions o = ReadJsonOptions<LoopClosureOptions>(json, "x.json:lcd");
  EXPECT_DOUBLE_EQ(o.vocabulary.nndr_ratio, 0.7);
  EXPECT_EQ(o.vocabulary.index.binary_kind, IndexKind::kLsh);
  EXPECT_EQ(o.vocabulary.index.checks, 64);
  EXPECT_EQ(o.vocabulary.max_features_per_node, 400);
  EXPECT_DOUBLE_EQ(o.bayes.virtual_place_prior, 0.8);
  EXPECT_DOUBLE_EQ(o.loop_threshold, 0.2);
  const ProximityOptions p =
      ReadJsonOptions<ProximityOptions>(nlohmann::json::parse(R"({"max_paths": 1})"), "x.json:proximity");
  EXPECT_EQ(p.max_paths, 1);
  EXPECT_DOUBLE_EQ(p.local_radius_m, 1.0);
}

TEST(LcdOptionsJson, RejectsUnknownKeysBadKindsAndBadValuesWithThePath) {
  auto message = [](const char* text) {
    try {
      ReadJsonOptions<LoopClosureOptions>(nlohmann::json::parse(text), "x.json:lcd");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"vocabulary": {"nndr": 0.7}})").find("x.json:lcd.vocabulary"), std::string::npos);
  EXPECT_NE(message(R"({"vocabulary": {"index": {"float_kind": "octree"}}})").find("octree"), std::string::npos);
  EXPECT_NE(message(R"({"loop_threshold": 3})").find("loop_threshold"), std::string::npos);
  EXPECT_THROW(ReadJsonOptions<ProximityOptions>(nlohmann::json::parse(R"({"forward_axis": [1, 0]})"), "p"),
               ConfigError);
}

}  // namespace
}  // namespace duskmap
