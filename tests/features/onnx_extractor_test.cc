#include "slam/features/onnx_extractor.h"

#include <cmath>
#include <functional>
#include <string>

#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

#include "slam/features/feature_factory.h"
#include "tests/features/onnx_test_models.h"
#include "tests/features/test_images.h"
#include "tests/testing/error_of.h"

namespace duskmap {
namespace {

using testing::ErrorOf;
using testing::MakeOnnxFeatureModel;

// The full-resolution dense model (score_map 1x1xHxW in (0, 1), descriptor_map
// 1x32xHxW): the map layout, stride 1.
OnnxFeatureOptions DenseMapContract(const std::string& model) {
  OnnxFeatureOptions o;
  o.model_path = model;
  o.score_layout = "map";
  o.descriptor_stride_px = 1;
  o.input_multiple_px = 1;
  o.nms_radius_px = 3;
  o.threshold = 0.5;
  return o;
}

OnnxFeatureOptions SparseContract(const std::string& model) {
  OnnxFeatureOptions o;
  o.model_path = model;
  o.contract = "sparse";
  o.threshold = 0.52;  // flat cells score 0.5
  return o;
}

void ExpectValidFeatures(const FrameFeatures& f, const cv::Size& image, int dims, float threshold,
                         int border) {
  ASSERT_EQ(f.descriptors.rows, static_cast<int>(f.size()));
  EXPECT_EQ(f.descriptors.cols, dims);
  EXPECT_EQ(f.descriptors.type(), CV_32F);
  for (size_t i = 0; i < f.size(); ++i) {
    const cv::KeyPoint& kp = f.keypoints[i];
    EXPECT_GT(kp.response, threshold);
    if (i > 0) {
      EXPECT_LE(kp.response, f.keypoints[i - 1].response);  // strongest first
    }
    EXPECT_GE(kp.pt.x, border);
    EXPECT_GE(kp.pt.y, border);
    EXPECT_LE(kp.pt.x, image.width - 1 - border);
    EXPECT_LE(kp.pt.y, image.height - 1 - border);
    EXPECT_NEAR(cv::norm(f.descriptors.row(static_cast<int>(i))), 1.0, 1e-4);
  }
}

TEST(OnnxExtractorTest, DenseFullResolutionMapModel) {
  const std::string model = MakeOnnxFeatureModel("onnx_dense.onnx", "--contract dense");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  const OnnxFeatureExtractor extractor(DenseMapContract(model), 400, 0.0);
  EXPECT_EQ(extractor.name(), "onnx");
  EXPECT_FALSE(extractor.DetectsOnColor());
  const cv::Mat image = testing::TexturedImage(203, 151, 7);
  const FrameFeatures f = extractor.Extract(image);
  ASSERT_GT(f.size(), 30u);
  EXPECT_LE(f.size(), 400u);
  ExpectValidFeatures(f, image.size(), 32, 0.5f, 4);
  for (size_t i = 0; i < f.size(); ++i) {  // NMS radius 3: only equal maxima that close
    EXPECT_EQ(f.keypoints[i].pt.x, std::floor(f.keypoints[i].pt.x));  // on pixels
    for (size_t j = 0; j < i; ++j) {
      const cv::Point2f d = f.keypoints[i].pt - f.keypoints[j].pt;
      if (f.keypoints[i].response == f.keypoints[j].response) continue;  // a plateau
      EXPECT_GT(std::max(std::abs(d.x), std::abs(d.y)), 3.0f);
    }
  }
  // Deterministic, and the same through the factory.
  FeatureOptions options;
  options.type = "onnx";
  options.max_features = 400;
  options.onnx = DenseMapContract(model);
  const FrameFeatures again = CreateFeatureExtractor(options)->Extract(image);
  ASSERT_EQ(again.size(), f.size());
  EXPECT_EQ(cv::norm(again.descriptors, f.descriptors, cv::NORM_INF), 0.0);
  // Without normalisation the rows are the map's raw values.
  OnnxFeatureOptions raw = DenseMapContract(model);
  raw.normalize_descriptors = false;
  const FrameFeatures unnormalised = OnnxFeatureExtractor(raw, 400, 0.0).Extract(image);
  ASSERT_EQ(unnormalised.size(), f.size());
  EXPECT_GT(std::abs(cv::norm(unnormalised.descriptors.row(0)) - 1.0), 1e-3);
}

TEST(OnnxExtractorTest, InputNormalisationChangesWhatTheModelSees) {
  const std::string model = MakeOnnxFeatureModel("onnx_dense.onnx", "--contract dense");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  const cv::Mat image = testing::TexturedImage(160, 120, 8);
  OnnxFeatureOptions plain = DenseMapContract(model);
  OnnxFeatureOptions centred = plain;
  centred.input_mean = {0.5};
  centred.input_std = {0.25};
  const FrameFeatures a = OnnxFeatureExtractor(plain, 1000, 0.0).Extract(image);
  const FrameFeatures b = OnnxFeatureExtractor(centred, 1000, 0.0).Extract(image);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  EXPECT_TRUE(a.size() != b.size() || cv::norm(a.descriptors, b.descriptors, cv::NORM_INF) > 0.0);
  // (x * 2/255 - 1) / 2 is x / 255 - 0.5: the same input as mean 0.5, std 1.
  OnnxFeatureOptions half = plain;
  half.input_mean = {0.5};
  OnnxFeatureOptions scaled = plain;
  scaled.input_scale = 2.0 / 255.0;
  scaled.input_mean = {1.0};
  scaled.input_std = {2.0};
  const FrameFeatures c = OnnxFeatureExtractor(half, 1000, 0.0).Extract(image);
  const FrameFeatures d = OnnxFeatureExtractor(scaled, 1000, 0.0).Extract(image);
  ASSERT_EQ(c.size(), d.size());
  EXPECT_LT(cv::norm(c.descriptors, d.descriptors, cv::NORM_INF), 1e-5);
}

TEST(OnnxExtractorTest, ColourInputGetsTheColourImageInTheDeclaredOrder) {
  const std::string model = MakeOnnxFeatureModel("onnx_dense_rgb.onnx", "--contract dense --rgb");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  cv::Mat bgr;
  cv::Mat planes[3] = {testing::TexturedImage(160, 120, 1), testing::TexturedImage(160, 120, 2),
                       testing::TexturedImage(160, 120, 3)};
  cv::merge(planes, 3, bgr);
  OnnxFeatureOptions rgb = DenseMapContract(model);
  rgb.input_color = "rgb";
  OnnxFeatureOptions bgr_order = rgb;
  bgr_order.input_color = "bgr";
  const OnnxFeatureExtractor rgb_extractor(rgb, 500, 0.0);
  EXPECT_TRUE(rgb_extractor.DetectsOnColor());
  const FrameFeatures from_rgb = rgb_extractor.Extract(bgr);
  ASSERT_GT(from_rgb.size(), 10u);
  ExpectValidFeatures(from_rgb, bgr.size(), 32, 0.5f, 4);
  // "bgr" on the channel-swapped image sees the same blob as "rgb" on the image.
  cv::Mat swapped;
  cv::cvtColor(bgr, swapped, cv::COLOR_BGR2RGB);
  const FrameFeatures from_bgr = OnnxFeatureExtractor(bgr_order, 500, 0.0).Extract(swapped);
  ASSERT_EQ(from_bgr.size(), from_rgb.size());
  EXPECT_EQ(cv::norm(from_bgr.descriptors, from_rgb.descriptors, cv::NORM_INF), 0.0);
  // A gray image is given to a colour model as three equal channels.
  EXPECT_NO_THROW(rgb_extractor.Extract(planes[0]));
  // A gray model refuses nothing either, but an RGB model declared gray does not run.
  OnnxFeatureOptions gray = rgb;
  gray.input_color = "gray";
  EXPECT_NE(ErrorOf([&] { OnnxFeatureExtractor(gray, 500, 0.0); })
                .find("network failed to run"),
            std::string::npos);
}

TEST(OnnxExtractorTest, SparseModelKeypointsDescriptorsAndScores) {
  const std::string model = MakeOnnxFeatureModel("onnx_sparse.onnx", "--contract sparse");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  const OnnxFeatureExtractor extractor(SparseContract(model), 2000, 0.0);
  const cv::Mat image = testing::TexturedImage(250, 190, 4);  // padded to 256x192
  const FrameFeatures f = extractor.Extract(image);
  // One keypoint per 8x8 cell of the padded image at most, minus border, padding and threshold.
  ASSERT_GT(f.size(), 100u);
  EXPECT_LE(f.size(), 32u * 24u);
  ExpectValidFeatures(f, image.size(), 32, 0.52f, 4);
  bool subpixel = false;
  for (const cv::KeyPoint& kp : f.keypoints) subpixel |= kp.pt.x != std::floor(kp.pt.x);
  EXPECT_TRUE(subpixel);
  // max_features keeps the strongest.
  const FrameFeatures few = OnnxFeatureExtractor(SparseContract(model), 50, 0.0).Extract(image);
  ASSERT_EQ(few.size(), 50u);
  for (size_t i = 0; i < few.size(); ++i) EXPECT_EQ(few.keypoints[i].pt, f.keypoints[i].pt);
  // COLMAP's pixel-corner origin moves every keypoint by half a pixel.
  OnnxFeatureOptions corner = SparseContract(model);
  corner.keypoint_origin = "pixel_corner";
  corner.border_px = 0;
  OnnxFeatureOptions centre = SparseContract(model);
  centre.border_px = 0;
  const FrameFeatures a = OnnxFeatureExtractor(centre, 2000, 0.0).Extract(image);
  const FrameFeatures b = OnnxFeatureExtractor(corner, 2000, 0.0).Extract(image);
  size_t compared = 0;
  for (const cv::KeyPoint& moved : b.keypoints) {
    bool found = false;
    for (const cv::KeyPoint& kp : a.keypoints) {
      if (kp.pt == moved.pt + cv::Point2f(0.5f, 0.5f)) {
        EXPECT_EQ(kp.response, moved.response);
        found = true;
        ++compared;
        break;
      }
    }
    // Only a keypoint the border dropped before the shift can be new.
    if (!found) {
      EXPECT_GT(std::max(moved.pt.x - (image.cols - 1), moved.pt.y - (image.rows - 1)), -0.5f);
    }
  }
  EXPECT_GT(compared, 100u);
  // Named outputs work as the defaults do; scores can be left out (then
  // every keypoint has response 1 and no threshold applies).
  OnnxFeatureOptions named = SparseContract(model);
  named.keypoints_output = "keypoints";
  named.descriptors_output = "descriptors";
  named.scores_output = "scores";
  EXPECT_EQ(OnnxFeatureExtractor(named, 2000, 0.0).Extract(image).size(), f.size());
}

TEST(OnnxExtractorTest, SparseColourModel) {
  const std::string model = MakeOnnxFeatureModel("onnx_sparse_rgb.onnx", "--contract sparse --rgb");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  OnnxFeatureOptions o = SparseContract(model);
  o.input_color = "rgb";
  o.input_mean = {0.485, 0.456, 0.406};  // ImageNet's, as ALIKED and DISK use
  o.input_std = {0.229, 0.224, 0.225};
  cv::Mat bgr;
  cv::cvtColor(testing::TexturedImage(200, 144, 9), bgr, cv::COLOR_GRAY2BGR);
  const FrameFeatures f = OnnxFeatureExtractor(o, 2000, 0.0).Extract(bgr);
  ASSERT_GT(f.size(), 50u);
  ExpectValidFeatures(f, bgr.size(), 32, 0.52f, 4);
}

TEST(OnnxExtractorTest, OutputsThatBreakTheContractAreNamed) {
  const std::string dense_bad = MakeOnnxFeatureModel("onnx_dense_malformed.onnx", "--contract dense --malformed");
  const std::string sparse_bad = MakeOnnxFeatureModel("onnx_sparse_malformed.onnx", "--contract sparse --malformed");
  const std::string dense = MakeOnnxFeatureModel("onnx_dense.onnx", "--contract dense");
  const std::string sparse = MakeOnnxFeatureModel("onnx_sparse.onnx", "--contract sparse");
  if (dense_bad.empty() || sparse_bad.empty() || dense.empty() || sparse.empty()) {
    GTEST_SKIP() << "python3-onnx unavailable: cannot write the test models";
  }
  auto error = [](const OnnxFeatureOptions& o) {
    return ErrorOf([&] { OnnxFeatureExtractor(o, 100, 0.0); });
  };
  // A two-channel score map.
  std::string e = error(DenseMapContract(dense_bad));
  EXPECT_NE(e.find("onnx_dense_malformed.onnx: the outputs do not match the declared dense contract"),
            std::string::npos) << e;
  EXPECT_NE(e.find("score_map 1x2x"), std::string::npos) << e;
  // A dense model read as SuperPoint-style cells.
  OnnxFeatureOptions cells = DenseMapContract(dense);
  cells.score_layout = "cells";
  cells.input_multiple_px = 8;
  e = error(cells);
  EXPECT_NE(e.find("needs a score output 1x65x(H/8)x(W/8)"), std::string::npos) << e;
  // Named outputs that do not exist or have the wrong shape.
  OnnxFeatureOptions named = DenseMapContract(dense);
  named.scores_output = "heatmap";
  EXPECT_NE(error(named).find("no output named heatmap"), std::string::npos) << error(named);
  named = DenseMapContract(dense);
  named.scores_output = "descriptor_map";
  EXPECT_NE(error(named).find("the score output descriptor_map is 1x32x"), std::string::npos)
      << error(named);
  named = DenseMapContract(dense);
  named.descriptor_dims = 128;
  EXPECT_NE(error(named).find("no descriptor output of that shape"), std::string::npos) << error(named);
  // Three keypoint coordinates.
  e = error(SparseContract(sparse_bad));
  EXPECT_NE(e.find("onnx_sparse_malformed.onnx: the outputs do not match the declared sparse contract: "
                   "keypoints must be 1xNx2 or Nx2, got 1x"),
            std::string::npos) << e;
  // Descriptors declared D x N, or of another width.
  OnnxFeatureOptions columns = SparseContract(sparse);
  columns.descriptors_layout = "d_by_n";
  EXPECT_NE(error(columns).find("descriptors must be 1xDxN or DxN"), std::string::npos) << error(columns);
  OnnxFeatureOptions wide = SparseContract(sparse);
  wide.descriptor_dims = 64;
  EXPECT_NE(error(wide).find("and D = 64, got 1x"), std::string::npos) << error(wide);
  // A dense model read as sparse.
  OnnxFeatureOptions as_sparse = SparseContract(dense);
  EXPECT_NE(error(as_sparse).find("no output named keypoints"), std::string::npos) << error(as_sparse);
}

// A NaN score map gave 0 features and a +inf one every pixel as a feature
// (1000 meaningless ones), both silently; a NaN descriptor map failed later
// without naming the model. The sparse contract refused the same already.
TEST(OnnxExtractorTest, NanOrInfiniteDenseMapsAreRefusedNamingTheModelAndTheOutput) {
  const std::string nan_scores =
      MakeOnnxFeatureModel("onnx_dense_nan_scores.onnx", "--contract dense --poison-scores nan");
  const std::string inf_scores =
      MakeOnnxFeatureModel("onnx_dense_inf_scores.onnx", "--contract dense --poison-scores inf");
  const std::string nan_descriptors = MakeOnnxFeatureModel(
      "onnx_dense_nan_descriptors.onnx", "--contract dense --poison-descriptors nan");
  const std::string inf_descriptors = MakeOnnxFeatureModel(
      "onnx_dense_inf_descriptors.onnx", "--contract dense --poison-descriptors inf");
  if (nan_scores.empty() || inf_scores.empty() || nan_descriptors.empty() ||
      inf_descriptors.empty()) {
    GTEST_SKIP() << "python3-onnx unavailable: cannot write the test models";
  }
  const auto error = [](const OnnxFeatureOptions& o) {
    return ErrorOf([&] { OnnxFeatureExtractor(o, 1000, 0.0); });
  };
  EXPECT_EQ(error(DenseMapContract(nan_scores)),
            nan_scores + ": the model's score output score_map holds NaN or infinite values");
  EXPECT_EQ(error(DenseMapContract(inf_scores)),
            inf_scores + ": the model's score output score_map holds NaN or infinite values");
  // Also through a sigmoid, which would have turned +inf into 1 everywhere.
  OnnxFeatureOptions sigmoid = DenseMapContract(inf_scores);
  sigmoid.score_activation = "sigmoid";
  EXPECT_EQ(error(sigmoid),
            inf_scores + ": the model's score output score_map holds NaN or infinite values");
  EXPECT_EQ(error(DenseMapContract(nan_descriptors)),
            nan_descriptors +
                ": the model's descriptor output descriptor_map holds NaN or infinite values");
  EXPECT_EQ(error(DenseMapContract(inf_descriptors)),
            inf_descriptors +
                ": the model's descriptor output descriptor_map holds NaN or infinite values");
}

TEST(OnnxExtractorTest, MissingUnreadableAndUnimportableModels) {
  OnnxFeatureOptions o;
  EXPECT_NE(ErrorOf([&] { OnnxFeatureExtractor(o, 100, 0.0); })
                .find("features.onnx.model_path: no ONNX model given"),
            std::string::npos);
  o.model_path = std::string(DUSKMAP_BINARY_DIR) + "/no_such_model.onnx";
  EXPECT_NE(ErrorOf([&] { OnnxFeatureExtractor(o, 100, 0.0); })
                .find("no_such_model.onnx: ONNX model not found"),
            std::string::npos);
  const std::string topk = MakeOnnxFeatureModel("onnx_topk.onnx", "--contract sparse --topk");
  if (topk.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  o = SparseContract(topk);
  const std::string e = ErrorOf([&] { OnnxFeatureExtractor(o, 100, 0.0); });
  EXPECT_NE(e.find("onnx_topk.onnx: not a readable ONNX model: OpenCV's DNN module has no TopK "
                   "layer (export the model's score and descriptor maps and use the dense contract)"),
            std::string::npos) << e;
}

TEST(OnnxExtractorTest, OptionsAreChecked) {
  auto error = [](const std::function<void(OnnxFeatureOptions*)>& change) {
    OnnxFeatureOptions o;
    change(&o);
    return ErrorOf([&] { o.Check(); });
  };
  EXPECT_NE(error([](auto* o) { o->contract = "grid"; }).find("features.onnx.contract: 'grid' unknown (dense, sparse, patch)"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->input_color = "rgba"; }).find("features.onnx.input_color"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->input_mean = {0.1, 0.2}; }).find("features.onnx.input_mean"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->input_std = {0.0}; }).find("features.onnx.input_std"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->input_scale = -1.0; }).find("features.onnx.input_scale"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->cell_size_px = 16; }).find("a multiple of cell_size_px"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->descriptor_stride_px = 3; }).find("a multiple of descriptor_stride_px"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->score_activation = "relu"; }).find("features.onnx.score_activation"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->descriptors_layout = "rows"; }).find("features.onnx.descriptors_layout"),
            std::string::npos);
  EXPECT_NE(error([](auto* o) { o->nms_radius_px = -1; }).find("features.onnx.nms_radius_px"),
            std::string::npos);
  OnnxFeatureOptions rgb;
  rgb.input_color = "rgb";
  rgb.input_mean = {0.485, 0.456, 0.406};
  rgb.input_std = {0.229, 0.224, 0.225};
  EXPECT_NO_THROW(rgb.Check());
  OnnxFeatureOptions sparse;
  sparse.contract = "sparse";
  sparse.cell_size_px = 16;  // dense-only sizes are not checked for a sparse model
  EXPECT_NO_THROW(sparse.Check());
}

}  // namespace
}  // namespace duskmap
