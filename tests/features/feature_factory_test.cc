// Every feature type built through the factory, on synthetic warps of a
// textured image: repeatability and matching score follow the invariances
// each method claims.
#include <set>

#include <gtest/gtest.h>

#include "slam/features/eval/homography_metrics.h"
#include "slam/features/feature_factory.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

const std::set<std::string> kRotationInvariant = {"surf", "sift", "brisk", "kaze",
                                                  "orb",  "akaze", "freak"};
const std::set<std::string> kScaleInvariant = {"surf", "sift", "kaze", "akaze"};

class FactoryTest : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() { reference_ = new cv::Mat(testing::TexturedImage()); }
  static void TearDownTestSuite() { delete reference_; }

  void SetUp() override {
    FeatureOptions options;
    options.type = GetParam();
    extractor_ = CreateFeatureExtractor(options);
    reference_features_ = extractor_->Extract(*reference_);
  }
  PairMetrics Against(const cv::Mat& target, const cv::Matx33d& h) const {
    return EvaluatePair(reference_features_, reference_->size(), extractor_->Extract(target),
                        target.size(), h, HomographyMetricsOptions());
  }

  static cv::Mat* reference_;
  std::unique_ptr<FeatureExtractor> extractor_;
  FrameFeatures reference_features_;
};
cv::Mat* FactoryTest::reference_ = nullptr;

TEST_P(FactoryTest, ExtractsStrongestFirstWithinTheCap) {
  const FrameFeatures& f = reference_features_;
  EXPECT_EQ(extractor_->name().substr(0, GetParam().size()), GetParam());
  ASSERT_GT(f.size(), 300u);
  EXPECT_LE(f.size(), 1000u);
  EXPECT_EQ(f.descriptors.rows, static_cast<int>(f.size()));
  EXPECT_EQ(f.points_in_camera.size(), f.size());
  EXPECT_FALSE(f.HasPoint(0));  // no depth given
  EXPECT_EQ(f.descriptors.type(), f.kind == DescriptorKind::kBinary ? CV_8U : CV_32F);
  for (size_t i = 1; i < f.size(); ++i) {
    ASSERT_GE(std::abs(f.keypoints[i - 1].response), std::abs(f.keypoints[i].response));
  }
  EXPECT_EQ(VocabularyDescriptors(f, 400).rows, std::min(400, static_cast<int>(f.size())));
}

TEST_P(FactoryTest, IsDeterministic) {
  const FrameFeatures again = extractor_->Extract(*reference_);
  ASSERT_EQ(again.size(), reference_features_.size());
  EXPECT_EQ(cv::norm(again.descriptors, reference_features_.descriptors, cv::NORM_INF), 0.0);
  for (size_t i = 0; i < again.size(); ++i) {
    EXPECT_EQ(again.keypoints[i].pt, reference_features_.keypoints[i].pt);
  }
}

TEST_P(FactoryTest, BrightnessContrastBlurAndNoise) {
  const cv::Matx33d identity = cv::Matx33d::eye();
  cv::Mat darker, blurred;
  // DAISY's histograms are raw gradients, as the reference's default
  // (NRM_NONE) leaves them: linear in contrast (daisy_test.cc), so it gets
  // a pure brightness change.
  if (GetParam() == "daisy") {
    reference_->convertTo(darker, CV_8U, 1.0, -25.0);
  } else {
    reference_->convertTo(darker, CV_8U, 0.6, 40.0);
  }
  cv::GaussianBlur(*reference_, blurred, cv::Size(0, 0), 1.5);
  const PairMetrics light = Against(darker, identity);
  EXPECT_GT(light.matching_score, 0.4);
  EXPECT_GT(light.repeatability, 0.5);
  EXPECT_TRUE(light.homography_correct);
  EXPECT_GT(Against(blurred, identity).matching_score, 0.3);
  EXPECT_GT(Against(testing::AddNoise(*reference_, 6.0, 3), identity).matching_score, 0.4);
}

TEST_P(FactoryTest, RotationFollowsTheClaimedInvariance) {
  cv::Matx33d h;
  const PairMetrics small = Against(testing::WarpRotateScale(*reference_, 10.0, 1.0, &h), h);
  EXPECT_GT(small.matching_score, 0.3);  // every type tolerates a small rotation
  const PairMetrics large = Against(testing::WarpRotateScale(*reference_, 40.0, 1.0, &h), h);
  EXPECT_GT(large.repeatability, 0.5);  // the detectors themselves are rotation-invariant
  if (kRotationInvariant.count(GetParam())) {
    EXPECT_GT(large.matching_score, 0.3);
    EXPECT_TRUE(large.homography_correct);
  } else {  // BRIEF, DAISY without orientation
    EXPECT_LT(large.matching_score, 0.1);
  }
}

TEST_P(FactoryTest, ScaleInvariantTypesMatchAcrossScale) {
  if (!kScaleInvariant.count(GetParam())) GTEST_SKIP() << GetParam() << " claims no scale invariance";
  cv::Matx33d h;
  const PairMetrics m = Against(testing::WarpRotateScale(*reference_, 0.0, 1.4, &h), h);
  EXPECT_GT(m.matching_score, 0.3);
  EXPECT_TRUE(m.homography_correct);
}

INSTANTIATE_TEST_SUITE_P(AllTypes, FactoryTest,
                         ::testing::Values("surf", "sift", "brief", "brisk", "kaze", "daisy", "orb",
                                           "akaze", "freak"),
                         [](const auto& info) { return info.param; });

TEST(FactoryTest, SuperPointWithoutModelIsAClearError) {
  FeatureOptions options;
  options.type = "superpoint";
  EXPECT_THROW(CreateFeatureExtractor(options), InputError);
  options.superpoint.model_path = "/nonexistent/superpoint.onnx";
  try {
    CreateFeatureExtractor(options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/superpoint.onnx"), std::string::npos);
  }
}

TEST(FactoryTest, UnknownTypeIsAConfigError) {
  FeatureOptions options;
  options.type = "harris";
  EXPECT_THROW(CreateFeatureExtractor(options), ConfigError);
}

}  // namespace
}  // namespace duskmap
