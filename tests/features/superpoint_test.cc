#include "slam/features/superpoint.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/features/test_images.h"

namespace duskmap {
namespace {

// Writes the architecture-identical random-weight model with the project's
// script; empty when Python/onnx are unavailable.
std::string MakeModel(const std::string& file, const std::string& flags = "") {
  const std::string path = std::string(DUSKMAP_BINARY_DIR) + "/" + file;
  if (std::filesystem::exists(path)) return path;
  const std::string python =
      std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string command = python + " " + DUSKMAP_SOURCE_DIR +
                              "/scripts/make_test_superpoint_onnx.py " + path + " " + flags +
                              " > /dev/null 2>&1";
  if (std::system(command.c_str()) != 0 || !std::filesystem::exists(path)) return "";
  return path;
}

TEST(SuperPointDecodingTest, DepthToSpaceOrderAndSoftmax) {
  // One cell; the logit of channel k = 8 r + c is large: the heat map peaks at (r, c).
  const int sizes[4] = {1, 65, 1, 2};
  cv::Mat semi(4, sizes, CV_32F, cv::Scalar(0.0f));
  semi.ptr<float>(0, 8 * 3 + 5)[0] = 10.0f;  // cell (0,0): row 3, col 5
  semi.ptr<float>(0, 64)[1] = 10.0f;         // cell (0,1): dustbin wins
  const cv::Mat heat = DecodeSuperPointHeatmap(semi);
  ASSERT_EQ(heat.size(), cv::Size(16, 8));
  cv::Point max_loc;
  double max_value;
  cv::minMaxLoc(heat.colRange(0, 8), nullptr, &max_value, nullptr, &max_loc);
  EXPECT_EQ(max_loc, cv::Point(5, 3));
  EXPECT_NEAR(max_value, std::exp(10.0) / (std::exp(10.0) + 64.0), 1e-5);
  EXPECT_NEAR(cv::sum(heat.colRange(0, 8))[0], 1.0 - 1.0 / (std::exp(10.0) + 64.0), 1e-5);
  EXPECT_LT(cv::sum(heat.colRange(8, 16))[0], 0.01);
}

TEST(SuperPointDecodingTest, NmsKeepsIsolatedMaxima) {
  cv::Mat scores(40, 40, CV_32F, cv::Scalar(0.0f));
  scores.at<float>(10, 10) = 0.9f;
  scores.at<float>(10, 13) = 0.5f;  // within radius 4 of a stronger peak
  scores.at<float>(30, 30) = 0.4f;  // isolated
  const cv::Mat kept = SuperPointNms(scores, 4);
  EXPECT_FLOAT_EQ(kept.at<float>(10, 10), 0.9f);
  EXPECT_FLOAT_EQ(kept.at<float>(10, 13), 0.0f);
  EXPECT_FLOAT_EQ(kept.at<float>(30, 30), 0.4f);
  EXPECT_EQ(cv::countNonZero(kept), 2);
}

TEST(SuperPointDecodingTest, DescriptorsAreBilinearAndUnitNorm) {
  const int sizes[4] = {1, 256, 2, 2};
  cv::Mat desc(4, sizes, CV_32F, cv::Scalar(0.0f));
  for (int c = 0; c < 256; ++c) {
    desc.ptr<float>(0, c)[0] = c == 0 ? 1.0f : 0.0f;  // cell (0,0) points along e0
    desc.ptr<float>(0, c)[1] = c == 1 ? 1.0f : 0.0f;  // cell (0,1) along e1
  }
  // Pixel 7.5 lies halfway between the centres (3.5 and 11.5) of cells 0 and 1.
  const cv::Mat d = SampleSuperPointDescriptors(desc, {cv::KeyPoint(7.5f, 3.5f, 8)});
  EXPECT_NEAR(d.at<float>(0, 0), std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(d.at<float>(0, 1), std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(cv::norm(d), 1.0, 1e-5);
}

TEST(SuperPointTest, MissingOrWrongModelIsAClearInputError) {
  SuperPointOptions options;
  EXPECT_THROW(SuperPointExtractor(options, 1000), InputError);
  options.model_path = std::string(DUSKMAP_BINARY_DIR) + "/not_a_model.onnx";
  std::ofstream(options.model_path) << "this is not an ONNX file";
  try {
    SuperPointExtractor extractor(options, 1000);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not_a_model.onnx"), std::string::npos);
  }
  const std::string wrong = MakeModel("superpoint_wrong_head.onnx", "--wrong-head");
  if (wrong.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  options.model_path = wrong;
  try {
    SuperPointExtractor extractor(options, 1000);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a SuperPoint model"), std::string::npos);
  }
}

TEST(SuperPointTest, RandomWeightModelDecodesToValidFeatures) {
  const std::string model = MakeModel("superpoint_random.onnx");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  SuperPointOptions options;
  options.model_path = model;
  const SuperPointExtractor extractor(options, 300);
  const cv::Mat image = testing::TexturedImage(250, 190, 3);  // not a multiple of 8: padded
  const FrameFeatures f = extractor.Extract(image);
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
  const FrameFeatures again = extractor.Extract(image);
  ASSERT_EQ(again.size(), f.size());
  EXPECT_EQ(cv::norm(again.descriptors, f.descriptors, cv::NORM_INF), 0.0);
  EXPECT_TRUE(extractor.Extract(cv::Mat(6, 6, CV_8UC1, cv::Scalar(3))).empty());
}

}  // namespace
}  // namespace duskmap
