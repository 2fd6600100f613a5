#include "slam/features/onnx_patch_extractor.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/file_checksum.h"
#include "slam/features/embedded_model.h"
#include "slam/features/feature_factory.h"
#include "slam/features/patch_sampler.h"
#include "tests/features/onnx_test_models.h"
#include "tests/features/test_images.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

// The patch contract on a model file (a declared onnx column's options).
FeatureOptions PatchOnnx(const std::string& model, int max_features = 300) {
  FeatureOptions o;
  o.type = "onnx";
  o.max_features = max_features;
  o.vocabulary_features = max_features;
  o.onnx.contract = "patch";
  o.onnx.model_path = model;
  return o;
}

// W (dims x area) then b (dims), float32, as make_test_onnx_patch.py writes them.
std::vector<float> ReadFloats(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  std::vector<float> values(static_cast<size_t>(in.tellg()) / sizeof(float));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  return values;
}

void ExpectSameKeypoints(const FrameFeatures& a, const FrameFeatures& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.keypoints[i].pt, b.keypoints[i].pt) << i;
    EXPECT_EQ(a.keypoints[i].size, b.keypoints[i].size) << i;
    EXPECT_EQ(a.keypoints[i].angle, b.keypoints[i].angle) << i;
    EXPECT_EQ(a.keypoints[i].response, b.keypoints[i].response) << i;
    EXPECT_EQ(a.keypoints[i].octave, b.keypoints[i].octave) << i;
  }
}

class OnnxPatchTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::ProcessTempDir("onnx_patch"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // A test model at dir_/<file> or a skip when python3-onnx is missing.
  std::string Model(const std::string& file, const std::string& flags) {
    const std::string path = dir_ + "/" + file;
    if (!testing::MakeOnnxPatchModel(path, flags)) return "";
    return path;
  }
  std::string dir_;
};

#define MODEL_OR_SKIP(var, file, flags)                                          \
  const std::string var = Model(file, flags);                                    \
  if (var.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write " file

// Descriptors against the linear model computed here: patches from the
// sampler, value (pixel / 255 - mean) / std, W x + b, L2-normalised; in
// batches of 7 (a remainder batch included); keypoints the sift type's.
TEST_F(OnnxPatchTest, DescriptorsMatchALinearReferenceOnSiftKeypoints) {
  MODEL_OR_SKIP(model, "linear.onnx", "--dims 16 --seed 3 --weights " + dir_ + "/linear.f32");
  FeatureOptions o = PatchOnnx(model, 60);
  o.onnx.batch_size = 7;
  o.onnx.input_mean = {0.5};
  o.onnx.input_std = {0.25};
  const cv::Mat image = testing::TexturedImage(320, 240, 21);
  const auto extractor = CreateFeatureExtractor(o);
  const FrameFeatures f = extractor->Extract(image);
  FeatureOptions sift = o;
  sift.type = "sift";
  ExpectSameKeypoints(f, CreateFeatureExtractor(sift)->Extract(image));
  ASSERT_GT(f.size(), 20u);
  ASSERT_NE(f.size() % 7, 0u);
  ASSERT_EQ(f.descriptors.rows, static_cast<int>(f.size()));
  ASSERT_EQ(f.descriptors.cols, 16);

  const std::vector<float> wb = ReadFloats(dir_ + "/linear.f32");
  const int area = 32 * 32;
  ASSERT_EQ(wb.size(), static_cast<size_t>(16 * area + 16));
  const cv::Mat w(16, area, CV_32F, const_cast<float*>(wb.data()));
  const cv::Mat b(1, 16, CV_32F, const_cast<float*>(wb.data()) + 16 * area);
  const cv::Mat patches = PatchSampler(image, PatchSamplerOptions()).Sample(f.keypoints);
  for (int i = 0; i < patches.rows; ++i) {
    cv::Mat x;
    patches.row(i).convertTo(x, CV_32F, 1.0 / 255.0 / 0.25, -0.5 / 0.25);
    cv::Mat expected = x * w.t() + b;
    expected /= cv::norm(expected);
    EXPECT_LT(cv::norm(expected, f.descriptors.row(i), cv::NORM_INF), 1e-4) << "keypoint " << i;
  }
}

// dusknet: the sift type's keypoints exactly (same options and count,
// strongest first), unit 128-D rows from the embedded model, which is the
// committed file's bytes.
TEST_F(OnnxPatchTest, DuskNetDescribesTheSiftTypesKeypointsWithTheEmbeddedModel) {
  FeatureOptions o;
  o.type = "dusknet";
  o.max_features = 400;
  const cv::Mat image = testing::TexturedImage(640, 480, 5);
  const auto extractor = CreateFeatureExtractor(o);
  EXPECT_EQ(extractor->name(), "dusknet");
  EXPECT_EQ(extractor->kind(), DescriptorKind::kFloat);
  const FrameFeatures f = extractor->Extract(image);
  o.type = "sift";
  ExpectSameKeypoints(f, CreateFeatureExtractor(o)->Extract(image));
  ASSERT_EQ(f.size(), 400u);
  ASSERT_EQ(f.descriptors.cols, 128);
  for (int i = 0; i < f.descriptors.rows; ++i) {
    EXPECT_NEAR(cv::norm(f.descriptors.row(i)), 1.0, 1e-4) << i;
  }
  const auto* patch = dynamic_cast<const OnnxPatchExtractor*>(extractor.get());
  ASSERT_NE(patch, nullptr);
  EXPECT_EQ(patch->model_name(), "embedded:dusknet.onnx");
  const EmbeddedModel& model = EmbeddedDuskNetModel();
  EXPECT_EQ(model.checksum_hex,
            FileChecksum64Hex(std::string(DUSKMAP_SOURCE_DIR) + "/slam/features/models/dusknet.onnx"));
  // Describe on given keypoints gives the same rows.
  const cv::Mat again = patch->Describe(image, f.keypoints);
  EXPECT_EQ(cv::norm(again, f.descriptors, cv::NORM_INF), 0.0);
}

// dusknet.model_path replaces the embedded model with a file.
TEST_F(OnnxPatchTest, DuskNetModelPathOverridesTheEmbeddedModel) {
  MODEL_OR_SKIP(model, "candidate.onnx", "--dims 128 --seed 9");
  FeatureOptions o;
  o.type = "dusknet";
  o.dusknet.model_path = model;
  const cv::Mat image = testing::TexturedImage(320, 240, 8);
  const auto from_file = CreateFeatureExtractor(o);
  EXPECT_EQ(dynamic_cast<const OnnxPatchExtractor&>(*from_file).model_name(), model);
  const FrameFeatures a = from_file->Extract(image);
  o.dusknet.model_path.clear();
  const FrameFeatures b = CreateFeatureExtractor(o)->Extract(image);
  ExpectSameKeypoints(a, b);
  ASSERT_GT(a.size(), 0u);
  EXPECT_GT(cv::norm(a.descriptors, b.descriptors, cv::NORM_INF), 0.01);  // another network
}

// Every model that breaks the contract is refused when the extractor is
// built, in one line naming the file.
TEST_F(OnnxPatchTest, ModelsThatBreakTheContractAreRefusedNamingTheFile) {
  MODEL_OR_SKIP(rgb, "rgb.onnx", "--input-channels 3");
  MODEL_OR_SKIP(large, "large.onnx", "--input-size 64");
  MODEL_OR_SKIP(rank3, "rank3.onnx", "--output-rank3");
  MODEL_OR_SKIP(nan, "nan.onnx", "--nan");
  MODEL_OR_SKIP(good, "good.onnx", "--dims 16");
  // Runs on 32x32 patches, but was declared (made) for 64x64 ones.
  MODEL_OR_SKIP(pooled, "pooled.onnx", "--input-size 64 --global-pool");
  MODEL_OR_SKIP(pooled32, "pooled32.onnx", "--global-pool");
  const auto error = [](const FeatureOptions& o) { return ErrorOf([&] { CreateFeatureExtractor(o); }); };
  const std::string declared = ": the patch contract needs input Nx1xPxP with P = patch_size_px = ";
  EXPECT_EQ(error(PatchOnnx(rgb)), rgb + declared + "32; the model declares its input 'patches' as ?x3x32x32");
  EXPECT_EQ(error(PatchOnnx(large)), large + declared + "32; the model declares its input 'patches' as ?x1x64x64");
  EXPECT_EQ(error(PatchOnnx(pooled)), pooled + declared + "32; the model declares its input 'patches' as ?x1x64x64");
  EXPECT_NO_THROW(CreateFeatureExtractor(PatchOnnx(pooled32)));
  FeatureOptions small_patch = PatchOnnx(good);  // the model wants 32x32
  small_patch.onnx.patch_size_px = 24;
  EXPECT_EQ(error(small_patch), good + declared + "24; the model declares its input 'patches' as ?x1x32x32");
  EXPECT_EQ(error(PatchOnnx(rank3)),
            rank3 + ": the patch contract needs an output NxD float (any D) for a 2x1x32x32 input, got 2x16x1");
  FeatureOptions wrong_dims = PatchOnnx(good);
  wrong_dims.onnx.descriptor_dims = 128;
  EXPECT_EQ(error(wrong_dims),
            good + ": the patch contract needs an output NxD float (D = 128) for a 2x1x32x32 input, got 2x16");
  EXPECT_EQ(error(PatchOnnx(nan)), nan + ": the model's output holds NaN or infinite values");
  EXPECT_EQ(error(PatchOnnx(dir_ + "/absent.onnx")), dir_ + "/absent.onnx: ONNX model not found");
  std::ofstream(dir_ + "/junk.onnx") << "not a protobuf";
  EXPECT_EQ(error(PatchOnnx(dir_ + "/junk.onnx")), dir_ + "/junk.onnx: not a readable ONNX model");
  EXPECT_EQ(error(PatchOnnx("")),
            "features.onnx.model_path: features of type onnx need the model's .onnx file");
  EXPECT_NO_THROW(CreateFeatureExtractor(PatchOnnx(good)));
}

// The patch options' checks, under the section of the type they belong to.
TEST(OnnxPatchOptions, CheckNamesTheField) {
  const auto error = [](FeatureOptions o) { return ErrorOf([&] { o.Check(); }); };
  FeatureOptions o;
  o.type = "dusknet";
  EXPECT_NO_THROW(o.Check());
  FeatureOptions bad = o;
  bad.dusknet.detector = "harris";
  EXPECT_EQ(error(bad), "features.dusknet.detector: 'harris' unknown (dog)");
  bad = o;
  bad.dusknet.patch_size_px = 7;
  EXPECT_NE(error(bad).find("features.dusknet.patch_size_px"), std::string::npos) << error(bad);
  bad = o;
  bad.dusknet.support_per_size = 0.0;
  EXPECT_NE(error(bad).find("features.dusknet.support_per_size"), std::string::npos) << error(bad);
  bad = o;
  bad.dusknet.batch_size = 0;
  EXPECT_NE(error(bad).find("features.dusknet.batch_size"), std::string::npos) << error(bad);
  bad = o;
  bad.dusknet.contract = "dense";  // the built-in type runs its patch model only
  EXPECT_EQ(ErrorOf([&] { CreateFeatureExtractor(bad); }),
            "features.dusknet.contract: the patch extractor runs the 'patch' contract, not 'dense'");
  FeatureOptions onnx = PatchOnnx("m.onnx");
  onnx.onnx.batch_size = -1;
  EXPECT_NE(error(onnx).find("features.onnx.batch_size"), std::string::npos) << error(onnx);
  onnx = PatchOnnx("m.onnx");
  onnx.onnx.input_color = "rgb";
  onnx.onnx.input_mean = {0.0};
  EXPECT_EQ(error(onnx), "features.onnx.input_color: the patch contract's input is gray");
}

}  // namespace
}  // namespace duskmap
