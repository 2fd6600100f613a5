#include "slam/experiment/engine_executor.h"

#include <string>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/experiment/experiment_config.h"
#include "slam/experiment/run_manifest.h"

namespace duskmap {
namespace {

std::string ErrorOf(const EngineOptions& base, const char* label) {
  try {
    EngineOptionsForFeature(base, FeatureSetupByLabel(label));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(EngineOptionsForFeature, ColumnsChooseExtractorAndMatcher) {
  EngineOptions base;
  base.features.superpoint.model_path = "models/superpoint.onnx";
  base.matcher.superglue.model_path = "models/superglue.onnx";
  const EngineOptions sift = EngineOptionsForFeature(base, FeatureSetupByLabel("SI"));
  EXPECT_EQ(sift.features.type, "sift");
  EXPECT_EQ(sift.matcher.type, "nndr");
  const EngineOptions sp = EngineOptionsForFeature(base, FeatureSetupByLabel("SP"));
  EXPECT_EQ(sp.features.type, "superpoint");
  EXPECT_EQ(sp.matcher.type, "nndr");
  const EngineOptions sg = EngineOptionsForFeature(base, FeatureSetupByLabel("SG"));
  EXPECT_EQ(sg.features.type, "superpoint");
  EXPECT_EQ(sg.matcher.type, "superglue");
  EXPECT_EQ(sg.matcher.superglue.model_path, "models/superglue.onnx");
}

TEST(EngineOptionsForFeature, LearnedColumnsNameTheMissingModel) {
  EngineOptions base;
  EXPECT_NE(ErrorOf(base, "SP").find("features.superpoint.model_path"), std::string::npos);
  base.features.superpoint.model_path = "models/superpoint.onnx";
  EXPECT_EQ(ErrorOf(base, "SP"), "");
  EXPECT_NE(ErrorOf(base, "SG").find("matcher.superglue.model_path"), std::string::npos);
}

TEST(SelectRunnableFeatures, SkipsLearnedColumnsWithoutTheirModelsAndSaysWhy) {
  ExperimentOptions options;
  options.features = {"SU", "SP", "SG"};
  const std::string existing = std::string(DUSKMAP_SOURCE_DIR) + "/configs/engine_paper.json";
  RunManifest manifest;
  SelectRunnableFeatures(options, {}, &manifest);
  EXPECT_EQ(manifest.features, std::vector<std::string>({"SU"}));
  ASSERT_EQ(manifest.skipped_features.size(), 2u);
  EXPECT_NE(manifest.skipped_features[0].reason.find("features.superpoint.model_path"), std::string::npos);
  // With a SuperPoint model (any existing file stands in) SP runs; SG still
  // needs its SuperGlue model, and a configured but absent file is named.
  SelectRunnableFeatures(options, {existing, "/no/such/superglue.onnx"}, &manifest);
  EXPECT_EQ(manifest.features, std::vector<std::string>({"SU", "SP"}));
  ASSERT_EQ(manifest.skipped_features.size(), 1u);
  EXPECT_EQ(manifest.skipped_features[0].label, "SG");
  EXPECT_NE(manifest.skipped_features[0].reason.find("/no/such/superglue.onnx"), std::string::npos);
  SelectRunnableFeatures(options, {existing, existing}, &manifest);
  EXPECT_EQ(manifest.features, std::vector<std::string>({"SU", "SP", "SG"}));
}

}  // namespace
}  // namespace duskmap
