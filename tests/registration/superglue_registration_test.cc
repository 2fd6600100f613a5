// Registration with the SuperGlue matcher (the paper's "111" runs): the
// window-guided second pass is skipped (spec appendix A: Reg/RepeatOnce
// false, Vis/CorGuessWinSize 0), while NNDR on the same pair runs it.
#include <cmath>

#include <gtest/gtest.h>

#include "slam/features/superglue.h"
#include "slam/registration/transform_estimation.h"
#include "tests/features/superglue_test_models.h"
#include "tests/registration/synthetic_pair.h"

namespace duskmap {
namespace {

// SuperGlue takes 256-D descriptors: each 128-D synthetic descriptor is
// repeated twice (row norms stay 1 after dividing by sqrt 2), which keeps
// the pair's correspondences and their noise.
void To256(FrameFeatures* f) {
  cv::Mat wide;
  cv::hconcat(f->descriptors, f->descriptors, wide);
  f->descriptors = wide / std::sqrt(2.0);
  for (cv::KeyPoint& kp : f->keypoints) kp.response = 0.5f;
}

TEST(SuperGlueRegistrationTest, SuperGlueMatcherSkipsTheGuidedSecondPass) {
  const std::string model = testing::MakeSuperGlueModel("superglue_random.onnx");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  testing::SyntheticPairOptions pair_options;
  pair_options.num_points = 200;
  pair_options.outlier_fraction = 0.2;
  testing::SyntheticPair pair = testing::MakeSyntheticPair(pair_options);
  To256(&pair.map_node);
  To256(&pair.query);
  SuperGlueOptions superglue;
  superglue.model_path = model;
  const SuperGlueMatcher matcher(superglue);
  RegistrationOptions options;
  ASSERT_TRUE(options.second_pass);  // the default, as Reg/RepeatOnce

  const RegistrationResult nndr = EstimateTransform(options, pair.map_node, pair.camera,
                                                    pair.query, pair.camera);
  ASSERT_TRUE(nndr.accepted()) << RegistrationStatusName(nndr.status);
  EXPECT_TRUE(nndr.second_pass_ran);

  const RegistrationResult result = EstimateTransform(options, pair.map_node, pair.camera,
                                                      pair.query, pair.camera, &matcher);
  ASSERT_TRUE(result.accepted()) << RegistrationStatusName(result.status);
  EXPECT_FALSE(result.second_pass_ran);
  EXPECT_EQ(result.matches_second_pass, 0);
  EXPECT_GE(result.num_inliers, options.min_inliers);
  const Rigid3d error = pair.node_from_query.Inverse() * result.node_from_query;
  EXPECT_LT(error.translation.norm(), 0.02);
  // Every final inlier is a SuperGlue match of a true correspondence.
  for (const cv::DMatch& m : result.inlier_matches) {
    EXPECT_TRUE(pair.query_is_inlier[m.queryIdx]) << "query feature " << m.queryIdx;
  }
}

}  // namespace
}  // namespace duskmap
