#include "slam/engine/engine_options.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(ReadEngineOptions, ReadsNestedValues) {
  const auto json = nlohmann::json::parse(R"({
    "features": {"type": "sift", "vocabulary_features": 300},
    "registration": {"min_inliers": 15},
    "loop_closure": {"loop_threshold": 0.2, "word_storage": "float32"},
    "proximity": {"local_radius_m": 2.0},
    "mapping": {"reduce_graph": true},
    "localization": {"proximity_max_paths": 2},
    "random_seed": 9})");
  JsonFields fields(json, "engine.json");
  const EngineOptions o = ReadEngineOptions(fields);
  EXPECT_EQ(o.features.type, "sift");
  EXPECT_EQ(o.registration.min_inliers, 15);
  EXPECT_TRUE(o.mapping.reduce_graph);
  EXPECT_EQ(o.LoopClosure().vocabulary.max_features_per_node, 300);
  EXPECT_DOUBLE_EQ(o.LoopClosure().loop_threshold, 0.2);
  EXPECT_EQ(o.LoopClosure().vocabulary.index.float_storage, DescriptorStorage::kFloat32);
  EXPECT_EQ(o.LocalizationProximity().max_paths, 2);
  EXPECT_EQ(o.MappingProximity().max_paths, 3);
  EXPECT_DOUBLE_EQ(o.MappingProximity().local_radius_m, 2.0);
  EXPECT_EQ(o.Registration().pnp.random_seed, 9u);
}

TEST(EngineOptions, DefaultsAreThePapersSettings) {
  // configs/engine_paper.json (the paper's runs) and the built-in defaults
  // must agree, so a config without engine_config runs the paper's settings.
  const EngineOptions paper =
      ReadEngineOptionsFile(std::string(DUSKMAP_SOURCE_DIR) + "/configs/engine_paper.json");
  EXPECT_EQ(EngineOptionsToJson(EngineOptions()).dump(2), EngineOptionsToJson(paper).dump(2));
  EXPECT_DOUBLE_EQ(EngineOptions().optimizer.max_error_ratio, 0.0);
  EXPECT_DOUBLE_EQ(EngineOptions().loop_closure.vocabulary.bad_signature_ratio, 0.2);
  EXPECT_EQ(EngineOptions().loop_closure.vocabulary.index.float_storage, DescriptorStorage::kUint8);
  // Kp/ByteToFloat true: binary descriptors by the L1 of their bytes, in the
  // vocabulary and in registration's first pass.
  EXPECT_EQ(paper.binary_distance, BinaryDistance::kByteL1);
  EXPECT_EQ(paper.LoopClosure().vocabulary.index.binary_distance, BinaryDistance::kByteL1);
  EXPECT_EQ(paper.Registration().matching.binary_distance, BinaryDistance::kByteL1);
  JsonFields hamming(nlohmann::json::parse(R"({"binary_distance": "hamming"})"), "engine.json");
  const EngineOptions exact = ReadEngineOptions(hamming);
  EXPECT_EQ(exact.LoopClosure().vocabulary.index.binary_distance, BinaryDistance::kHamming);
  EXPECT_EQ(exact.Registration().matching.binary_distance, BinaryDistance::kHamming);
  JsonFields unknown(nlohmann::json::parse(R"({"binary_distance": "l2"})"), "engine.json");
  EXPECT_THROW(ReadEngineOptions(unknown), ConfigError);
  JsonFields bad(nlohmann::json::parse(R"({"loop_closure": {"word_storage": "int4"}})"), "engine.json");
  EXPECT_THROW(ReadEngineOptions(bad), ConfigError);
}

TEST(ReadEngineOptions, RejectsUnknownKeysWithPath) {
  JsonFields fields(nlohmann::json::parse(R"({"mapping": {"reduce": true}})"), "engine.json");
  try {
    ReadEngineOptions(fields);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("engine.json.mapping"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reduce"), std::string::npos) << e.what();
  }
}

TEST(EngineOptions, CheckNamesField) {
  EngineOptions o;
  o.localization.odometry_cache_size = -1;
  EXPECT_THROW(o.Check(), ConfigError);
  o.localization.odometry_cache_size = 1;  // a cache needs two frames
  EXPECT_THROW(o.Check(), ConfigError);
  o.localization.odometry_cache_size = 10;
  EXPECT_NO_THROW(o.Check());
  o.localization.odometry_cache_max_error_ratio = 0.0;
  EXPECT_THROW(o.Check(), ConfigError);
  o = EngineOptions();
  o.odometry.linear_sigma_m = 0.0;
  try {
    o.Check();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("linear_sigma_m"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
