// The committed DuskNet model (docs/learned_descriptor.md) against the
// descriptors its training script wrote beside it
// (slam/features/models/dusknet_reference.json: 16 generated validation
// patches and OpenCV's DNN output for them). Fails when the embedded model,
// the patch contract's input scaling or the patch sampler's geometry drift
// from what the model was trained and exported with.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include "slam/features/embedded_model.h"
#include "slam/features/feature_options.h"
#include "slam/features/onnx_patch_extractor.h"

namespace duskmap {
namespace {

struct Reference {
  int patch_size_px = 0;
  std::vector<cv::Mat> patches;  // CV_8U patch_size_px x patch_size_px each
  cv::Mat descriptors;           // one CV_32F row per patch
};

Reference ReadReference() {
  const std::string path =
      std::string(DUSKMAP_SOURCE_DIR) + "/slam/features/models/dusknet_reference.json";
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  const nlohmann::json json = nlohmann::json::parse(in);
  Reference r;
  r.patch_size_px = json.at("patch_size_px").get<int>();
  const int p = r.patch_size_px;
  for (const auto& values : json.at("patches")) {
    cv::Mat patch(p, p, CV_8U);
    for (int i = 0; i < p * p; ++i) patch.at<uint8_t>(i / p, i % p) = values.at(i).get<uint8_t>();
    r.patches.push_back(patch);
  }
  for (const auto& values : json.at("descriptors")) {
    cv::Mat row(1, static_cast<int>(values.size()), CV_32F);
    for (int i = 0; i < row.cols; ++i) row.at<float>(0, i) = values.at(i).get<float>();
    r.descriptors.push_back(row);
  }
  return r;
}

TEST(DuskNetModel, EmbeddedModelGivesTheTrainingScriptsDescriptors) {
  const Reference ref = ReadReference();
  ASSERT_EQ(ref.patches.size(), 16u);
  ASSERT_EQ(ref.descriptors.rows, 16);
  ASSERT_EQ(ref.descriptors.cols, 128);
  const EmbeddedModel& model = EmbeddedDuskNetModel();
  cv::dnn::Net net = cv::dnn::readNetFromONNX(model.bytes, model.size);
  // The contract's input: N x 1 x P x P, pixel / 255.
  std::vector<cv::Mat> images;
  for (const cv::Mat& patch : ref.patches) {
    cv::Mat scaled;
    patch.convertTo(scaled, CV_32F, DuskNetFeatureOptions().input_scale);
    images.push_back(scaled);
  }
  net.setInput(cv::dnn::blobFromImages(images));
  const cv::Mat out = net.forward().reshape(1, static_cast<int>(images.size()));
  EXPECT_LE(cv::norm(out, ref.descriptors, cv::NORM_INF), 1e-5);
}

// Each patch placed in an image so that the sampler's patch is the patch
// itself: keypoints at the cell centres with size P / 6 (one image pixel per
// patch pixel, pyramid level 0) and angle 0.
TEST(DuskNetModel, DusknetTypeDescribesSampledPatchesAsTheModelDoes) {
  const Reference ref = ReadReference();
  const int p = ref.patch_size_px;
  const int cell = 2 * p;  // blank margin, so that bilinear samples stay inside each patch
  const int n = static_cast<int>(ref.patches.size());
  cv::Mat gray(cell, cell * n, CV_8U, cv::Scalar(0));
  std::vector<cv::KeyPoint> keypoints;
  for (int i = 0; i < n; ++i) {
    const int x0 = i * cell + p / 2, y0 = p / 2;
    ref.patches[i].copyTo(gray(cv::Rect(x0, y0, p, p)));
    keypoints.emplace_back(cv::Point2f(x0 + 0.5f * (p - 1), y0 + 0.5f * (p - 1)),
                           static_cast<float>(p / DuskNetFeatureOptions().support_per_size), 0.0f);
  }
  const OnnxPatchExtractor extractor(DuskNetFeatureOptions(), SiftOptions(), 1000, 0.0,
                                     FeatureTypeId::kDuskNet);
  const cv::Mat descriptors = extractor.Describe(gray, keypoints);
  ASSERT_EQ(descriptors.rows, n);
  EXPECT_LE(cv::norm(descriptors, ref.descriptors, cv::NORM_INF), 1e-5);
  // And they are discriminative: each patch's nearest reference descriptor is its own.
  for (int i = 0; i < n; ++i) {
    int nearest = -1;
    double best = 1e9;
    for (int j = 0; j < n; ++j) {
      const double d = cv::norm(descriptors.row(i), ref.descriptors.row(j));
      if (d < best) best = d, nearest = j;
    }
    EXPECT_EQ(nearest, i);
  }
}

}  // namespace
}  // namespace duskmap
