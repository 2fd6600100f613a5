#include "slam/features/feature_options.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "slam/features/feature_options_json.h"

namespace duskmap {
namespace {

TEST(FeatureOptionsTest, DefaultsAreThePapersSettings) {
  const FeatureOptions o;
  EXPECT_NO_THROW(o.Check());
  EXPECT_EQ(o.max_features, 1000);
  EXPECT_EQ(o.vocabulary_features, 400);
  EXPECT_EQ(o.surf.hessian_threshold, 100.0);
  EXPECT_EQ(o.sift.contrast_threshold, 0.02);
  EXPECT_EQ(o.brisk.threshold, 10);
  EXPECT_EQ(o.brief.bytes, 32);
  EXPECT_EQ(o.orb.edge_threshold, 19);
  EXPECT_EQ(o.orb.scale_factor, 2.0);
  EXPECT_EQ(o.orb.levels, 3);
  EXPECT_EQ(o.daisy.radius_px, 15.0);
  EXPECT_EQ(o.superpoint.threshold, 0.010);
  EXPECT_EQ(o.superpoint.nms_radius_px, 4);
  // The ten detectors, dusknet (the embedded model), onnx (any model) and h5 (imported).
  EXPECT_EQ(FeatureTypeNames().size(), 13u);
  EXPECT_EQ(o.h5.descriptor_kind, "float");
  EXPECT_EQ(o.h5.keypoint_origin, "pixel_centre");
}

// Command lines take a type in any case; the built-in types (no file
// needed) are the list's first nine, the default of features eval.
TEST(FeatureOptionsTest, TypeNamesInAnyCase) {
  EXPECT_EQ(FeatureTypeFromName("SURF", "--types"), "surf");
  EXPECT_EQ(FeatureTypeFromName("Sift", "--types"), "sift");
  EXPECT_EQ(FeatureTypeFromName("h5", "--types"), "h5");
  try {
    FeatureTypeFromName("SURFACE", "features eval: --types");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "features eval: --types: unknown feature type 'SURFACE' (known: surf, sift, brief, brisk, kaze, "
              "daisy, orb, akaze, freak, dusknet, superpoint, onnx, h5)");
  }
  const std::vector<std::string>& built_in = BuiltInFeatureTypeNames();
  ASSERT_EQ(built_in.size(), 10u);
  EXPECT_TRUE(std::equal(built_in.begin(), built_in.end(), FeatureTypeNames().begin()));
  for (const std::string& type : built_in) {
    FeatureOptions o;
    o.type = type;
    EXPECT_NO_THROW(o.Check()) << type;  // needs no model or file
  }
}

TEST(FeatureOptionsTest, ReadsJsonAndRejectsUnknownKeys) {
  const auto json = nlohmann::json::parse(
      R"({"type": "sift", "max_features": 800, "sift": {"contrast_threshold": 0.03},
          "surf": {"extended": true}})");
  JsonFields fields(json, "test.json:features");
  const FeatureOptions o = ReadJsonOptions<FeatureOptions>(fields);
  EXPECT_EQ(o.type, "sift");
  EXPECT_EQ(o.max_features, 800);
  EXPECT_EQ(o.sift.contrast_threshold, 0.03);
  EXPECT_TRUE(o.surf.extended);

  const auto typo = nlohmann::json::parse(R"({"sift": {"contrast_treshold": 0.03}})");
  JsonFields typo_fields(typo, "test.json:features");
  try {
    ReadJsonOptions<FeatureOptions>(typo_fields);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("contrast_treshold"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("test.json:features.sift"), std::string::npos);
  }
}

TEST(FeatureOptionsTest, ReadsAnOnnxContract) {
  const auto json = nlohmann::json::parse(
      R"({"type": "onnx", "onnx": {"model_path": "m.onnx", "contract": "dense",
          "input_color": "rgb", "input_mean": [0.485, 0.456, 0.406],
          "input_std": [0.229, 0.224, 0.225], "input_multiple_px": 16,
          "score_layout": "map", "score_activation": "sigmoid", "descriptor_stride_px": 1,
          "scores_output": "scores", "descriptors_output": "dense_desc", "descriptor_dims": 128,
          "nms_radius_px": 2, "threshold": 0.2, "border_px": 2,
          "normalize_descriptors": false}})");
  JsonFields fields(json, "test.json:features");
  const FeatureOptions o = ReadJsonOptions<FeatureOptions>(fields);
  EXPECT_EQ(o.type, "onnx");
  EXPECT_EQ(o.onnx.model_path, "m.onnx");
  EXPECT_EQ(o.onnx.input_color, "rgb");
  EXPECT_EQ(o.onnx.input_mean, (std::vector<double>{0.485, 0.456, 0.406}));
  EXPECT_EQ(o.onnx.input_std.size(), 3u);
  EXPECT_EQ(o.onnx.input_multiple_px, 16);
  EXPECT_EQ(o.onnx.score_layout, "map");
  EXPECT_EQ(o.onnx.score_activation, "sigmoid");
  EXPECT_EQ(o.onnx.descriptor_stride_px, 1);
  EXPECT_EQ(o.onnx.scores_output, "scores");
  EXPECT_EQ(o.onnx.descriptors_output, "dense_desc");
  EXPECT_EQ(o.onnx.descriptor_dims, 128);
  EXPECT_EQ(o.onnx.nms_radius_px, 2);
  EXPECT_EQ(o.onnx.threshold, 0.2);
  EXPECT_EQ(o.onnx.border_px, 2);
  EXPECT_FALSE(o.onnx.normalize_descriptors);

  // An onnx type needs its model; unknown keys and values are named.
  const auto no_model = nlohmann::json::parse(R"({"type": "onnx"})");
  JsonFields no_model_fields(no_model, "test.json:features");
  EXPECT_THROW(ReadJsonOptions<FeatureOptions>(no_model_fields), ConfigError);
  const auto typo = nlohmann::json::parse(R"({"onnx": {"model": "m.onnx"}})");
  JsonFields typo_fields(typo, "test.json:features");
  try {
    ReadJsonOptions<FeatureOptions>(typo_fields);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("test.json:features.onnx"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("model"), std::string::npos) << e.what();
  }
  const auto layout = nlohmann::json::parse(R"({"onnx": {"score_layout": "grid"}})");
  JsonFields layout_fields(layout, "test.json:features");
  try {
    ReadJsonOptions<FeatureOptions>(layout_fields);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("features.onnx.score_layout: 'grid' unknown (cells, map)"),
              std::string::npos)
        << e.what();
  }
}

TEST(FeatureOptionsTest, CheckNamesTheBadField) {
  FeatureOptions o;
  o.brief.bytes = 20;
  try {
    o.Check();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("brief.bytes"), std::string::npos);
  }
  o = FeatureOptions();
  o.vocabulary_features = 2000;
  EXPECT_THROW(o.Check(), ConfigError);
  o = FeatureOptions();
  o.type = "sirf";
  EXPECT_THROW(o.Check(), ConfigError);
  o = FeatureOptions();
  o.freak.detector = "harris";
  EXPECT_THROW(o.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
