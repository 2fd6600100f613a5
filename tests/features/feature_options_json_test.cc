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

}  // namespace
}  // namespace duskmap
