#include "slam/registration/transform_estimation.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/registration/synthetic_pair.h"
#include "tests/testing/rigid3d_near.h"

namespace duskmap {
namespace {

using testing::MakeSyntheticPair;
using testing::Rigid3dNear;
using testing::SyntheticPair;
using testing::SyntheticPairOptions;

RegistrationResult Estimate(const SyntheticPair& pair, const RegistrationOptions& options = {}) {
  return EstimateTransform(options, pair.map_node, pair.camera, pair.query, pair.camera);
}

TEST(EstimateTransform, RecoversPoseWithHalfOutliersFloat) {
  SyntheticPairOptions data;
  data.num_points = 300;
  data.outlier_fraction = 0.5;
  const SyntheticPair pair = MakeSyntheticPair(data);
  const RegistrationResult result = Estimate(pair);
  ASSERT_TRUE(result.accepted()) << RegistrationStatusName(result.status);
  EXPECT_THAT(result.node_from_query, Rigid3dNear(pair.node_from_query, 0.01, 0.5));
  EXPECT_GE(result.num_inliers, 120);
  EXPECT_LE(result.num_inliers, 150 + 5);  // outliers do not sneak in
  // Half the global matches are outliers; the guided pass mostly finds inliers.
  EXPECT_NEAR(double(result.inliers_first_pass) / result.matches_first_pass, 0.5, 0.1);
  EXPECT_GT(result.inlier_ratio, 0.8);
  EXPECT_TRUE(result.information.allFinite());
  EXPECT_GT(result.information(0, 0), 0.0);
  EXPECT_EQ(result.inlier_matches.size(), static_cast<size_t>(result.num_inliers));
  for (const cv::DMatch& m : result.inlier_matches) {
    EXPECT_TRUE(pair.query_is_inlier[m.queryIdx]);
  }
  EXPECT_GT(result.timings.total_ms, 0.0);
}

TEST(EstimateTransform, RecoversPoseWithHalfOutliersBinaryAndQueryDepth) {
  SyntheticPairOptions data;
  data.kind = DescriptorKind::kBinary;
  data.query_depth = true;
  data.seed = 7;
  const SyntheticPair pair = MakeSyntheticPair(data);
  const RegistrationResult result = Estimate(pair);
  ASSERT_TRUE(result.accepted()) << RegistrationStatusName(result.status);
  EXPECT_THAT(result.node_from_query, Rigid3dNear(pair.node_from_query, 0.01, 0.5));
}

TEST(EstimateTransform, RejectsBelowMinInliersWithReason) {
  SyntheticPairOptions data;
  data.num_points = 60;
  data.outlier_fraction = 45.0 / 60.0;  // 15 geometric inliers, 45 matched outliers
  const SyntheticPair pair = MakeSyntheticPair(data);
  const RegistrationResult result = Estimate(pair);
  EXPECT_EQ(result.status, RegistrationStatus::kTooFewInliers);
  EXPECT_STREQ(RegistrationStatusName(result.status), "too_few_inliers");
  EXPECT_GE(result.matches_first_pass, 20);
  EXPECT_LT(result.num_inliers, 20);
  EXPECT_GE(result.num_inliers, 12);
  EXPECT_TRUE(result.node_from_query.IsFinite());
  EXPECT_TRUE(result.inlier_matches.empty());

  RegistrationOptions lenient;
  lenient.min_inliers = 10;
  EXPECT_TRUE(Estimate(pair, lenient).accepted());
}

TEST(EstimateTransform, SecondPassRecoversAmbiguousFeatures) {
  SyntheticPairOptions data;
  data.num_points = 300;
  data.outlier_fraction = 0.0;
  data.twin_features = 200;  // ambiguous for global NNDR, unique in a 40 px window
  data.seed = 3;
  const SyntheticPair pair = MakeSyntheticPair(data);

  RegistrationOptions one_pass;
  one_pass.second_pass = false;
  const RegistrationResult first_only = Estimate(pair, one_pass);
  const RegistrationResult both = Estimate(pair);
  ASSERT_TRUE(first_only.accepted()) << RegistrationStatusName(first_only.status);
  ASSERT_TRUE(both.accepted()) << RegistrationStatusName(both.status);
  EXPECT_TRUE(both.second_pass_ran);
  EXPECT_FALSE(first_only.second_pass_ran);
  EXPECT_GT(both.inliers_second_pass, both.inliers_first_pass + 100);
  EXPECT_GT(both.num_inliers, first_only.num_inliers + 100);
  EXPECT_THAT(both.node_from_query, Rigid3dNear(pair.node_from_query, 0.01, 0.5));
}

TEST(EstimateTransform, FailedSecondPassFailsTheRegistration) {
  SyntheticPairOptions data;
  data.pixel_noise_px = 1.0;
  const SyntheticPair pair = MakeSyntheticPair(data);
  RegistrationOptions tiny_window;
  tiny_window.guess_window_px = 0.01;  // no query keypoint within 0.01 px of a projection
  const RegistrationResult result = Estimate(pair, tiny_window);
  EXPECT_EQ(result.status, RegistrationStatus::kSecondPassTooFewMatches);
  EXPECT_TRUE(result.second_pass_ran);
  EXPECT_GE(result.inliers_first_pass, 20);  // the first pass alone would have been accepted
  EXPECT_EQ(result.node_from_query.translation, Eigen::Vector3d::Zero());
}

// The map node's 3D points rotated by 180 deg about y (all behind its camera,
// as with a sign error in depth): PnP still finds a consistent query pose
// (the points are in front of the query camera), but the bundle adjustment
// has no observation in front of the map node's camera and fails.
TEST(EstimateTransform, BundleAdjustmentFailureRejectsWithItsStatus) {
  SyntheticPair pair = MakeSyntheticPair({});
  const Eigen::Matrix3d flip = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (Eigen::Vector3f& p : pair.map_node.points_in_camera) p = (flip * p.cast<double>()).cast<float>();
  const RegistrationResult result = Estimate(pair);
  EXPECT_EQ(result.status, RegistrationStatus::kBundleAdjustmentFailed);
  EXPECT_STREQ(RegistrationStatusName(result.status), "ba_failed");
  EXPECT_GE(result.inliers_second_pass, 100);  // both PnP passes succeeded before it
  EXPECT_FALSE(result.accepted());
  EXPECT_EQ(result.node_from_query.translation, Eigen::Vector3d::Zero());  // no pose carried
  EXPECT_TRUE(result.inlier_matches.empty());
  // Without bundle adjustment the same pair is accepted with the pose that
  // explains the rotated points: BA is the step that rejected it.
  RegistrationOptions no_ba;
  no_ba.bundle_adjustment.enabled = false;
  const RegistrationResult without = Estimate(pair, no_ba);
  ASSERT_TRUE(without.accepted()) << RegistrationStatusName(without.status);
  EXPECT_THAT(without.node_from_query,
              Rigid3dNear(Rigid3d(flip, Eigen::Vector3d::Zero()) * pair.node_from_query, 0.01, 0.5));
}

TEST(EstimateTransform, VarianceLimitRejects) {
  const SyntheticPair pair = MakeSyntheticPair({});  // no query depth: 10 % depth error term
  RegistrationOptions strict;
  strict.information.max_linear_variance_m2 = 1e-6;
  const RegistrationResult result = Estimate(pair, strict);
  EXPECT_EQ(result.status, RegistrationStatus::kVarianceTooHigh);
  EXPECT_STREQ(RegistrationStatusName(result.status), "variance_too_high");
  EXPECT_GE(result.num_inliers, 20);
}

TEST(EstimateTransform, DeterministicForFixedSeed) {
  SyntheticPairOptions data;
  data.seed = 11;
  const SyntheticPair pair = MakeSyntheticPair(data);
  for (NndrSearch search : {NndrSearch::kBruteForce, NndrSearch::kKdTree}) {
    RegistrationOptions options;
    options.matching.search = search;
    const RegistrationResult a = Estimate(pair, options);
    const RegistrationResult b = Estimate(pair, options);
    ASSERT_TRUE(a.accepted());
    EXPECT_EQ(a.node_from_query.translation, b.node_from_query.translation);
    EXPECT_EQ(a.node_from_query.rotation.coeffs(), b.node_from_query.rotation.coeffs());
    EXPECT_EQ(a.num_inliers, b.num_inliers);
    EXPECT_EQ(a.matches_first_pass, b.matches_first_pass);
    EXPECT_EQ(a.information, b.information);
    ASSERT_EQ(a.inlier_matches.size(), b.inlier_matches.size());
    for (size_t i = 0; i < a.inlier_matches.size(); ++i) {
      EXPECT_EQ(a.inlier_matches[i].queryIdx, b.inlier_matches[i].queryIdx);
      EXPECT_EQ(a.inlier_matches[i].trainIdx, b.inlier_matches[i].trainIdx);
    }
  }
}

TEST(EstimateTransform, ExternalMatcherSkipsSecondPass) {
  // Stands in for a learned matcher: any FeatureMatcher other than the default.
  class ExternalMatcher : public FeatureMatcher {
   public:
    std::string name() const override { return "external"; }
    std::vector<cv::DMatch> Match(const FrameFeatures& query, const cv::Size&,
                                  const FrameFeatures& train, const cv::Size&) const override {
      return NndrMatcher().Match(query, {}, train, {});
    }
  };
  const SyntheticPair pair = MakeSyntheticPair({});
  const ExternalMatcher matcher;
  const RegistrationResult result =
      EstimateTransform({}, pair.map_node, pair.camera, pair.query, pair.camera, &matcher);
  ASSERT_TRUE(result.accepted());
  EXPECT_FALSE(result.second_pass_ran);
  RegistrationOptions with_second;
  with_second.second_pass_with_external_matcher = true;
  EXPECT_TRUE(EstimateTransform(with_second, pair.map_node, pair.camera, pair.query, pair.camera,
                                &matcher)
                  .second_pass_ran);
}

TEST(EstimateTransform, NonFiniteMapPointsAreIgnored) {
  SyntheticPair pair = MakeSyntheticPair({});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < pair.map_node.size(); i += 3) {
    pair.map_node.points_in_camera[i] = Eigen::Vector3f(i % 2 ? nan : inf, 0.0f, 1.0f);
  }
  const RegistrationResult partial = Estimate(pair);
  ASSERT_TRUE(partial.accepted()) << RegistrationStatusName(partial.status);
  EXPECT_THAT(partial.node_from_query, Rigid3dNear(pair.node_from_query, 0.01, 0.5));

  for (Eigen::Vector3f& p : pair.map_node.points_in_camera) p.setConstant(nan);
  const RegistrationResult none = Estimate(pair);
  EXPECT_EQ(none.status, RegistrationStatus::kNoFeatures);
  EXPECT_TRUE(none.node_from_query.IsFinite());
}

TEST(EstimateTransform, NonFiniteKeypointsAreIgnored) {
  SyntheticPair pair = MakeSyntheticPair({});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t i = 0; i < pair.map_node.size(); i += 4) pair.map_node.keypoints[i].pt.x = nan;
  for (size_t i = 1; i < pair.query.size(); i += 4) pair.query.keypoints[i].pt.y = nan;
  const RegistrationResult result = Estimate(pair);
  ASSERT_TRUE(result.accepted()) << RegistrationStatusName(result.status);
  EXPECT_THAT(result.node_from_query, Rigid3dNear(pair.node_from_query, 0.01, 0.5));
  for (const cv::DMatch& m : result.inlier_matches) {
    EXPECT_FALSE(std::isnan(pair.map_node.keypoints[m.trainIdx].pt.x));
    EXPECT_FALSE(std::isnan(pair.query.keypoints[m.queryIdx].pt.y));
  }
}

TEST(EstimateTransform, ZeroFeaturesGiveNoFeaturesStatus) {
  const SyntheticPair pair = MakeSyntheticPair({});
  const FrameFeatures empty;
  EXPECT_EQ(EstimateTransform({}, pair.map_node, pair.camera, empty, pair.camera).status,
            RegistrationStatus::kNoFeatures);
  EXPECT_EQ(EstimateTransform({}, empty, pair.camera, pair.query, pair.camera).status,
            RegistrationStatus::kNoFeatures);
}

TEST(EstimateTransform, IdenticalDescriptorsGiveTooFewMatches) {
  SyntheticPair pair = MakeSyntheticPair({});
  pair.map_node.descriptors.setTo(0.1f);
  pair.query.descriptors.setTo(0.1f);
  const RegistrationResult result = Estimate(pair);
  EXPECT_EQ(result.status, RegistrationStatus::kTooFewMatches);
  EXPECT_EQ(result.matches_first_pass, 0);
  EXPECT_TRUE(result.node_from_query.IsFinite());
}

TEST(EstimateTransform, CollinearPointsAreRejectedWithFinitePose) {
  SyntheticPairOptions data;
  data.outlier_fraction = 0.0;
  SyntheticPair pair = MakeSyntheticPair(data);
  const Rigid3d query_from_node = pair.node_from_query.Inverse();
  // Move every map point onto one 3D line and its query keypoint onto the
  // line's projection.
  for (size_t i = 0; i < pair.map_node.size(); ++i) {
    const double s = static_cast<double>(i) / pair.map_node.size();
    pair.map_node.points_in_camera[i] = Eigen::Vector3f(-0.5f + float(s), 0.2f, 3.0f);
  }
  // Query keypoints are the projections of the (now collinear) points.
  for (size_t k = 0; k < pair.query.size(); ++k) {
    double best = std::numeric_limits<double>::infinity();
    int train = 0;
    for (int j = 0; j < pair.map_node.descriptors.rows; ++j) {
      const double d = cv::norm(pair.query.descriptors.row(k), pair.map_node.descriptors.row(j));
      if (d < best) {
        best = d;
        train = j;
      }
    }
    Eigen::Vector2d px;
    ASSERT_TRUE(pair.camera.Project(
        query_from_node * pair.map_node.points_in_camera[train].cast<double>(), &px));
    pair.query.keypoints[k].pt = cv::Point2f(px.x(), px.y());
  }
  const RegistrationResult result = Estimate(pair);
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(result.status == RegistrationStatus::kPnpFailed ||
              result.status == RegistrationStatus::kTooFewInliers)
      << RegistrationStatusName(result.status);
  EXPECT_TRUE(result.node_from_query.IsFinite());
}

TEST(EstimateTransform, InconsistentInputsThrow) {
  SyntheticPair pair = MakeSyntheticPair({});
  SyntheticPair rows = pair;
  rows.query.descriptors = rows.query.descriptors.rowRange(0, 10).clone();
  EXPECT_THROW(Estimate(rows), InputError);

  SyntheticPair points = pair;
  points.map_node.points_in_camera.pop_back();
  EXPECT_THROW(Estimate(points), InputError);

  SyntheticPairOptions binary;
  binary.kind = DescriptorKind::kBinary;
  const SyntheticPair other = MakeSyntheticPair(binary);
  EXPECT_THROW(
      EstimateTransform({}, pair.map_node, pair.camera, other.query, pair.camera), InputError);

  PinholeCamera bad = pair.camera;
  bad.fx = 0.0;
  EXPECT_THROW(EstimateTransform({}, pair.map_node, pair.camera, pair.query, bad), InputError);

  RegistrationOptions options;
  options.min_inliers = 3;
  EXPECT_THROW(Estimate(pair, options), ConfigError);
}

// A proximity link's length limit (spec §5.4): only an accepted transform
// longer than the limit is refused; its estimate stays for the records.
TEST(RejectLongerThan, RefusesOnlyAcceptedTransformsBeyondTheLimit) {
  RegistrationResult result;
  result.status = RegistrationStatus::kAccepted;
  result.node_from_query.translation = Eigen::Vector3d(0.6, 0.0, 0.8);  // 1 m
  RejectLongerThan(1.0, &result);
  EXPECT_EQ(result.status, RegistrationStatus::kAccepted);
  RejectLongerThan(0.99, &result);
  EXPECT_EQ(result.status, RegistrationStatus::kTranslationTooLong);
  EXPECT_DOUBLE_EQ(result.node_from_query.translation.norm(), 1.0);
  RegistrationResult rejected;
  rejected.status = RegistrationStatus::kTooFewInliers;
  rejected.node_from_query.translation = Eigen::Vector3d(5.0, 0.0, 0.0);
  RejectLongerThan(1.0, &rejected);
  EXPECT_EQ(rejected.status, RegistrationStatus::kTooFewInliers);
  RegistrationResult not_finite;
  not_finite.status = RegistrationStatus::kAccepted;
  not_finite.node_from_query.translation = Eigen::Vector3d(std::nan(""), 0.0, 0.0);
  RejectLongerThan(1.0, &not_finite);
  EXPECT_EQ(not_finite.status, RegistrationStatus::kTranslationTooLong);
}

}  // namespace
}  // namespace duskmap
