#include "slam/features/feature_options.h"

#include <gtest/gtest.h>

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
  EXPECT_EQ(FeatureTypeNames().size(), 11u);  // the ten detectors and h5 (imported)
  EXPECT_EQ(o.h5.descriptor_kind, "float");
  EXPECT_EQ(o.h5.keypoint_origin, "pixel_centre");
}

TEST(FeatureOptionsTest, ReadsJsonAndRejectsUnknownKeys) {
  const auto json = nlohmann::json::parse(
      R"({"type": "sift", "max_features": 800, "sift": {"contrast_threshold": 0.03},
          "surf": {"extended": true}})");
  JsonFields fields(json, "test.json:features");
  const FeatureOptions o = ReadFeatureOptions(fields);
  EXPECT_EQ(o.type, "sift");
  EXPECT_EQ(o.max_features, 800);
  EXPECT_EQ(o.sift.contrast_threshold, 0.03);
  EXPECT_TRUE(o.surf.extended);

  const auto typo = nlohmann::json::parse(R"({"sift": {"contrast_treshold": 0.03}})");
  JsonFields typo_fields(typo, "test.json:features");
  try {
    ReadFeatureOptions(typo_fields);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("contrast_treshold"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("test.json:features.sift"), std::string::npos);
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
