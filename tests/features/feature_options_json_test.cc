#include "slam/features/feature_options_json.h"

#include <gtest/gtest.h>

#include "tests/testing/error_of.h"

namespace duskmap {
namespace {

TEST(FeatureOptionsJsonTest, AMapsStoredOptionsReadBackAsWritten) {
  FeatureOptions o;
  o.type = "onnx";
  o.max_features = 700;
  o.sift.contrast_threshold = 0.03;
  o.onnx.model_path = "models/aliked.onnx";
  o.onnx.score_layout = "map";
  o.onnx.descriptor_stride_px = 1;
  o.onnx.input_color = "rgb";
  o.onnx.input_mean = {0.485, 0.456, 0.406};
  o.onnx.input_std = {0.229, 0.224, 0.225};
  o.h5.path = "feats.h5";
  const std::string text = ToJsonObject(o).dump();
  const FeatureOptions back = FeatureOptionsOfMap(text, "m.db");
  EXPECT_EQ(ToJsonObject(back), ToJsonObject(o));
  EXPECT_EQ(back.onnx.input_mean, o.onnx.input_mean);
  EXPECT_EQ(back.sift.contrast_threshold, 0.03);

  // A map of an older version stored fewer keys: the others keep their defaults.
  const FeatureOptions old = FeatureOptionsOfMap(R"({"type": "sift", "max_features": 900})", "old.db");
  EXPECT_EQ(old.type, "sift");
  EXPECT_EQ(old.max_features, 900);
  EXPECT_EQ(old.onnx.score_layout, "cells");

  EXPECT_EQ(testing::ErrorOf([] { FeatureOptionsOfMap("{", "bad.db"); }),
            "bad.db: feature_parameters: not JSON (the map is damaged; rebuild it)");
  EXPECT_NE(testing::ErrorOf([] { FeatureOptionsOfMap(R"({"colour": 1})", "odd.db"); })
                .find("odd.db: feature_parameters"),
            std::string::npos);
}

// The dusknet section: the patch contract's defaults, read and written back
// under the type's registered name, its errors under it too.
TEST(FeatureOptionsJsonTest, DuskNetOptionsRoundTrip) {
  const FeatureOptions defaults;
  EXPECT_EQ(defaults.dusknet.contract, "patch");
  EXPECT_EQ(defaults.dusknet.detector, "dog");
  EXPECT_EQ(defaults.dusknet.patch_size_px, 32);
  EXPECT_EQ(defaults.dusknet.descriptor_dims, 128);
  EXPECT_TRUE(defaults.dusknet.model_path.empty());  // the embedded model
  const nlohmann::json json = ToJsonObject(defaults);
  ASSERT_TRUE(json.contains("dusknet")) << json.dump();
  EXPECT_EQ(json["dusknet"]["contract"], "patch");

  FeatureOptions o;
  o.type = "dusknet";
  o.dusknet.model_path = "candidates/epoch_12.onnx";
  o.dusknet.batch_size = 64;
  o.dusknet.support_per_size = 5.0;
  o.dusknet.oriented = false;
  const FeatureOptions back = FeatureOptionsOfMap(ToJsonObject(o).dump(), "m.db");
  EXPECT_EQ(ToJsonObject(back), ToJsonObject(o));
  EXPECT_EQ(back.dusknet.model_path, "candidates/epoch_12.onnx");
  EXPECT_EQ(back.dusknet.batch_size, 64);
  EXPECT_FALSE(back.dusknet.oriented);
  EXPECT_NO_THROW(back.Check());

  o.dusknet.batch_size = 0;
  EXPECT_NE(testing::ErrorOf([&] { o.Check(); }).find("features.dusknet.batch_size"), std::string::npos);
}

}  // namespace
}  // namespace duskmap
