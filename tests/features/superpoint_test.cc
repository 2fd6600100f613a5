#include "slam/features/superpoint.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/features/feature_factory.h"
#include "slam/features/onnx_extractor.h"
#include "tests/features/onnx_test_models.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

using testing::MakeSuperPointModel;

TEST(SuperPointTest, MissingOrWrongModelIsAClearInputError) {
  SuperPointOptions options;
  EXPECT_THROW(CreateSuperPointExtractor(options, 1000), InputError);
  options.model_path = std::string(DUSKMAP_BINARY_DIR) + "/not_a_model.onnx";
  std::ofstream(options.model_path) << "this is not an ONNX file";
  try {
    CreateSuperPointExtractor(options, 1000);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not_a_model.onnx"), std::string::npos);
  }
  const std::string wrong = MakeSuperPointModel("superpoint_wrong_head.onnx", "--wrong-head");
  if (wrong.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  options.model_path = wrong;
  try {
    CreateSuperPointExtractor(options, 1000);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("superpoint_wrong_head.onnx: not a SuperPoint model"), std::string::npos)
        << message;
    EXPECT_NE(message.find("1x65x(H/8)x(W/8)"), std::string::npos) << message;
    EXPECT_NE(message.find("semi 1x64x"), std::string::npos) << message;  // what the model gives
  }
}

TEST(SuperPointTest, RandomWeightModelDecodesToValidFeatures) {
  const std::string model = MakeSuperPointModel("superpoint_random.onnx");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  SuperPointOptions options;
  options.model_path = model;
  const std::unique_ptr<FeatureExtractor> extractor = CreateSuperPointExtractor(options, 300);
  EXPECT_EQ(extractor->name(), "superpoint");
  const cv::Mat image = testing::TexturedImage(250, 190, 3);  // not a multiple of 8: padded
  const FrameFeatures f = extractor->Extract(image);
  ASSERT_GT(f.size(), 20u);
  EXPECT_LE(f.size(), 300u);
  EXPECT_EQ(f.descriptors.cols, 256);
  EXPECT_EQ(f.DescriptorBytes(), 1024u);
  for (size_t i = 0; i < f.size(); ++i) {
    const cv::KeyPoint& kp = f.keypoints[i];
    EXPECT_GT(kp.response, 0.010f);
    EXPECT_GE(kp.pt.x, 4.0f);
    EXPECT_GE(kp.pt.y, 4.0f);
    EXPECT_LT(kp.pt.x, image.cols - 4.0f);
    EXPECT_LT(kp.pt.y, image.rows - 4.0f);
    EXPECT_NEAR(cv::norm(f.descriptors.row(static_cast<int>(i))), 1.0, 1e-4);
    for (size_t j = 0; j < i; ++j) {  // NMS radius 4: no two keypoints that close
      const cv::Point2f d = kp.pt - f.keypoints[j].pt;
      EXPECT_GT(std::max(std::abs(d.x), std::abs(d.y)), 4.0f);
    }
  }
  const FrameFeatures again = extractor->Extract(image);
  ASSERT_EQ(again.size(), f.size());
  EXPECT_EQ(cv::norm(again.descriptors, f.descriptors, cv::NORM_INF), 0.0);
  EXPECT_TRUE(extractor->Extract(cv::Mat(6, 6, CV_8UC1, cv::Scalar(3))).empty());
}

// The superpoint type is the onnx type under SuperPoint's contract, and that
// contract is the onnx type's default: the same model gives the same
// features, bit for bit, through "superpoint", through SuperPointContract and
// through "onnx" with only the model path set.
TEST(SuperPointTest, IsTheOnnxTypeWithSuperPointsContract) {
  const std::string model = MakeSuperPointModel("superpoint_random.onnx");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  FeatureOptions superpoint;
  superpoint.type = "superpoint";
  superpoint.superpoint.model_path = model;
  superpoint.superpoint.threshold = 0.02;
  superpoint.max_features = 500;
  FeatureOptions onnx = superpoint;
  onnx.type = "onnx";
  onnx.onnx = SuperPointContract(superpoint.superpoint);
  FeatureOptions onnx_defaults = superpoint;
  onnx_defaults.type = "onnx";
  onnx_defaults.onnx.model_path = model;
  onnx_defaults.onnx.threshold = 0.02;
  const cv::Mat image = testing::TexturedImage(320, 240, 5);
  const FrameFeatures expected = CreateFeatureExtractor(superpoint)->Extract(image);
  ASSERT_GT(expected.size(), 50u);
  for (const FeatureOptions& options : {onnx, onnx_defaults}) {
    const FrameFeatures got = CreateFeatureExtractor(options)->Extract(image);
    ASSERT_EQ(got.size(), expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got.keypoints[i].pt, expected.keypoints[i].pt);
      EXPECT_EQ(got.keypoints[i].response, expected.keypoints[i].response);
    }
    EXPECT_EQ(cv::norm(got.descriptors, expected.descriptors, cv::NORM_INF), 0.0);
  }
}

}  // namespace
}  // namespace duskmap
