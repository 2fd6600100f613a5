#include "slam/registration/pnp_ransac.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/registration/synthetic_pair.h"

namespace duskmap {
namespace {

struct PnpData {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  Rigid3d camera_from_points;
  PinholeCamera camera = testing::TestCamera();
};

PnpData MakeData(int inliers, int outliers, uint64_t seed) {
  PnpData d;
  d.camera_from_points = Rigid3d(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -1, 0.5).normalized())),
      Eigen::Vector3d(0.4, 0.1, -0.2));
  Rng rng(seed);
  std::uniform_real_distribution<double> u(0, 640), v(0, 480), z(1, 5);
  const Rigid3d points_from_camera = d.camera_from_points.Inverse();
  for (int i = 0; i < inliers + outliers; ++i) {
    const Eigen::Vector2d px(u(rng), v(rng));
    d.points.push_back(points_from_camera * d.camera.Unproject(px.x(), px.y(), z(rng)));
    d.pixels.push_back(i < inliers ? px : Eigen::Vector2d(u(rng), v(rng)));
  }
  return d;
}

TEST(EstimatePnpRansac, ExactPoseWithHalfOutliers) {
  for (PnpMinimalSolver solver : {PnpMinimalSolver::kP3P, PnpMinimalSolver::kAP3P}) {
    const PnpData d = MakeData(100, 100, 5);
    PnpRansacOptions options;
    options.solver = solver;
    const PnpResult result = EstimatePnpRansac(options, d.points, d.pixels, d.camera);
    ASSERT_TRUE(result.success);
    EXPECT_LT((result.camera_from_points.translation - d.camera_from_points.translation).norm(),
              1e-6);
    EXPECT_LT(RotationAngleRad(result.camera_from_points.rotation, d.camera_from_points.rotation),
              1e-6);
    EXPECT_GE(result.inliers.size(), 100u);
    EXPECT_LE(result.inliers.size(), 105u);
    for (int i = 0; i < 100; ++i) {
      EXPECT_LT(ReprojectionErrorPx(d.camera, result.camera_from_points, d.points[i], d.pixels[i]),
                1e-6);
    }
  }
}

TEST(EstimatePnpRansac, TooFewCorrespondencesFail) {
  const PnpData d = MakeData(3, 0, 6);
  const PnpResult result = EstimatePnpRansac({}, d.points, d.pixels, d.camera);
  EXPECT_FALSE(result.success);
  EXPECT_TRUE(result.camera_from_points.IsFinite());
}

TEST(ReprojectionErrorPx, BehindCameraIsInfinite) {
  const PinholeCamera camera = testing::TestCamera();
  EXPECT_TRUE(std::isinf(ReprojectionErrorPx(camera, Rigid3d(), Eigen::Vector3d(0, 0, -1),
                                             Eigen::Vector2d(320, 240))));
  EXPECT_NEAR(ReprojectionErrorPx(camera, Rigid3d(), Eigen::Vector3d(0, 0, 2),
                                  Eigen::Vector2d(322.5, 243.5)),
              5.0, 1e-9);
}

TEST(PnpRansacOptions, CheckNamesField) {
  PnpRansacOptions options;
  options.max_reprojection_error_px = -1.0;
  try {
    options.Check();
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("max_reprojection_error_px"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
