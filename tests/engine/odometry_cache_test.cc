// The odometry-cache validation of localizations (spec §9.2): one
// localization alone is never applied, a consistent second one is, and a
// wrong one (inconsistent with the cached odometry and localizations) is
// rejected and not kept.
#include "slam/engine/odometry_cache.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

Information6d RegistrationLikeInformation() {
  Information6d information = Information6d::Zero();
  for (int i = 0; i < 3; ++i) information(i, i) = 1.0 / (0.02 * 0.02);
  for (int i = 3; i < 6; ++i) information(i, i) = 1.0 / (0.01 * 0.01);
  return information;
}

// A robot driving along x in its odometry frame; the map frame is the
// odometry frame moved and turned; two map nodes along the route.
class OdometryCacheTest : public ::testing::Test {
 protected:
  Rigid3d OdomFromCamera(int frame) const {
    return Rigid3d(Eigen::AngleAxisd(0.02 * frame, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                   Eigen::Vector3d(0.1 * frame, 0.0, 0.0));
  }
  // The true node_camera_from_query of `frame` against `node_pose`.
  Rigid3d TrueLink(const Rigid3d& map_from_node, int frame) const {
    return map_from_node.Inverse() * map_from_odom_ * OdomFromCamera(frame);
  }
  const Rigid3d map_from_odom_{
      Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()).toRotationMatrix(),
      Eigen::Vector3d(2.0, 0.1, -3.0)};
  const Rigid3d node_a_{Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                        Eigen::Vector3d(2.2, 0.0, -3.1)};
  const Rigid3d node_b_{Eigen::AngleAxisd(0.75, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                        Eigen::Vector3d(2.6, 0.1, -3.4)};
};

TEST_F(OdometryCacheTest, SingleLocalizationWaitsAndConsistentSecondIsApplied) {
  OdometryCache cache(OdometryCacheOptions{});
  cache.AddFrame(OdomFromCamera(0));
  const CacheValidationResult first =
      cache.Validate(7, node_a_, TrueLink(node_a_, 0), RegistrationLikeInformation());
  EXPECT_EQ(first.status, CacheValidation::kWaiting);
  EXPECT_EQ(cache.num_localization_links(), 1u);
  for (int frame = 1; frame <= 3; ++frame) cache.AddFrame(OdomFromCamera(frame));
  const CacheValidationResult second =
      cache.Validate(12, node_b_, TrueLink(node_b_, 3), RegistrationLikeInformation());
  EXPECT_EQ(second.status, CacheValidation::kApplied)
      << second.max_linear_ratio << " " << second.max_angular_ratio;
  EXPECT_LT(second.max_linear_ratio, 0.1);
  EXPECT_EQ(second.localization_links, 2);
  EXPECT_EQ(cache.num_localization_links(), 2u);
}

TEST_F(OdometryCacheTest, WrongLocalizationIsRejectedAndNotKept) {
  OdometryCache cache(OdometryCacheOptions{});
  cache.AddFrame(OdomFromCamera(0));
  cache.Validate(7, node_a_, TrueLink(node_a_, 0), RegistrationLikeInformation());
  cache.AddFrame(OdomFromCamera(1));
  ASSERT_EQ(cache.Validate(7, node_a_, TrueLink(node_a_, 1), RegistrationLikeInformation()).status,
            CacheValidation::kApplied);
  cache.AddFrame(OdomFromCamera(2));
  // A wrong re-localization: 0.6 m and 8 degrees off (e.g. a look-alike place).
  const Rigid3d error(Eigen::AngleAxisd(0.14, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                      Eigen::Vector3d(0.6, 0.0, 0.1));
  const CacheValidationResult wrong =
      cache.Validate(12, node_b_, TrueLink(node_b_, 2) * error, RegistrationLikeInformation());
  EXPECT_EQ(wrong.status, CacheValidation::kRejected);
  EXPECT_GT(std::max(wrong.max_linear_ratio, wrong.max_angular_ratio), 3.0);
  EXPECT_EQ(cache.num_localization_links(), 2u);
  // The next correct one is still accepted.
  cache.AddFrame(OdomFromCamera(3));
  EXPECT_EQ(cache.Validate(12, node_b_, TrueLink(node_b_, 3), RegistrationLikeInformation()).status,
            CacheValidation::kApplied);
}

TEST_F(OdometryCacheTest, LocalizationsLeaveWithTheirFrames) {
  OdometryCacheOptions options;
  options.size = 3;
  OdometryCache cache(options);
  cache.AddFrame(OdomFromCamera(0));
  cache.Validate(7, node_a_, TrueLink(node_a_, 0), RegistrationLikeInformation());
  for (int frame = 1; frame <= 3; ++frame) cache.AddFrame(OdomFromCamera(frame));
  EXPECT_EQ(cache.num_frames(), 3u);
  EXPECT_EQ(cache.num_localization_links(), 0u);
  // Alone again: waits.
  EXPECT_EQ(cache.Validate(12, node_b_, TrueLink(node_b_, 3), RegistrationLikeInformation()).status,
            CacheValidation::kWaiting);
}

TEST(OdometryCacheOptionsTest, CheckRejectsBadValues) {
  OdometryCacheOptions options;
  options.size = 1;
  EXPECT_THROW(options.Check(), ConfigError);
  options = OdometryCacheOptions{};
  options.max_error_ratio = 0.0;
  EXPECT_THROW(options.Check(), ConfigError);
  OdometryCache cache(OdometryCacheOptions{});
  EXPECT_THROW(cache.Validate(1, Rigid3d(), Rigid3d(), RegistrationLikeInformation()), InputError);
}

}  // namespace
}  // namespace duskmap
