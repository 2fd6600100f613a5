// Correspondence geometry against analytic scenes: a plane seen from two
// known poses (the projection is the plane's homography), an occluder in B's
// depth, and the predicted scale and angle for a turn about the optical axis
// and a move along it.
#include "slam/training/correspondence.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

PinholeCamera TestCamera() {
  PinholeCamera camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 525.0;
  camera.cx = 319.5;
  camera.cy = 239.5;
  return camera;
}

// The exact depth of the world plane n . x = d seen from `world_from_camera`
// (0 where the ray misses it or meets it behind the camera).
cv::Mat PlaneDepth(const PinholeCamera& camera, const Rigid3d& world_from_camera, const Eigen::Vector3d& n,
                   double d) {
  cv::Mat depth(camera.height, camera.width, CV_32F, cv::Scalar(0));
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray = world_from_camera.rotation * camera.Unproject(u, v, 1.0);
      const double denominator = n.dot(ray);
      if (std::abs(denominator) < 1e-9) continue;
      const double z = (d - n.dot(world_from_camera.translation)) / denominator;
      if (z > 0.0) depth.at<float>(v, u) = static_cast<float>(z);
    }
  }
  return depth;
}

// A facing the plane z = 3 from the origin; B as given.
struct PlanePair {
  ViewGeometry a;
  ViewGeometry b;
};

PlanePair MakePlanePair(const Rigid3d& world_from_b) {
  const Eigen::Vector3d n(0, 0, 1);
  PlanePair pair;
  pair.a = {PlaneDepth(TestCamera(), Rigid3d(), n, 3.0), TestCamera(), Rigid3d()};
  pair.b = {PlaneDepth(TestCamera(), world_from_b, n, 3.0), TestCamera(), world_from_b};
  return pair;
}

cv::KeyPoint Key(float x, float y, float size, float angle_deg) { return cv::KeyPoint(x, y, size, angle_deg); }

TEST(Correspondence, PlanePointLandsWhereTheHomographySays) {
  const Rigid3d world_from_b(Eigen::Quaterniond(Eigen::AngleAxisd(0.15, Eigen::Vector3d(0.2, 1, 0.1).normalized())),
                             Eigen::Vector3d(0.3, -0.1, 0.4));
  const PlanePair pair = MakePlanePair(world_from_b);
  // H = K (R - t n^T / d) K^-1 with B's pose relative to A and the plane z = 3 in A.
  const Rigid3d b_from_a = world_from_b.Inverse();
  Eigen::Matrix3d k;
  k << 525, 0, 319.5, 0, 525, 239.5, 0, 0, 1;
  const Eigen::Matrix3d h = k *
                            (b_from_a.rotation.toRotationMatrix() +
                             b_from_a.translation * Eigen::Vector3d(0, 0, 1).transpose() / 3.0) *
                            k.inverse();
  int checked = 0;
  for (float x : {100.3f, 250.7f, 320.0f, 480.2f}) {
    for (float y : {90.6f, 240.1f, 400.9f}) {
      const PredictedKeypoint p = PredictKeypoint(Key(x, y, 8, 0), pair.a, pair.b, 0.03);
      const Eigen::Vector3d expected = h * Eigen::Vector3d(x, y, 1);
      if (p.status == PredictionStatus::kOutsideImage) continue;
      ASSERT_EQ(p.status, PredictionStatus::kVisible) << x << " " << y;
      EXPECT_NEAR(p.pt_in_b.x, expected.x() / expected.z(), 1e-3);
      EXPECT_NEAR(p.pt_in_b.y, expected.y() / expected.z(), 1e-3);
      EXPECT_NEAR(p.point_in_world.z(), 3.0, 1e-5);
      ++checked;
    }
  }
  EXPECT_GE(checked, 8);
}

TEST(Correspondence, OccluderInBsDepthRejectsThePoint) {
  PlanePair pair = MakePlanePair(Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.2, 0, 0)));
  const cv::KeyPoint key = Key(300.2f, 200.4f, 8, 0);
  const PredictedKeypoint visible = PredictKeypoint(key, pair.a, pair.b, 0.03);
  ASSERT_EQ(visible.status, PredictionStatus::kVisible);
  // A box 1 m in front of the plane covers the point in B only.
  cv::rectangle(pair.b.depth_m, cv::Rect(static_cast<int>(visible.pt_in_b.x) - 10, static_cast<int>(visible.pt_in_b.y) - 10, 20, 20),
                cv::Scalar(2.0), cv::FILLED);
  EXPECT_EQ(PredictKeypoint(key, pair.a, pair.b, 0.03).status, PredictionStatus::kOccluded);
  // Within the tolerance (2 % nearer) it is the same surface.
  pair.b.depth_m.setTo(cv::Scalar(0.98 * 3.0));
  EXPECT_EQ(PredictKeypoint(key, pair.a, pair.b, 0.03).status, PredictionStatus::kVisible);
  // No depth at A's pixel, or nothing seen in B: no prediction.
  pair.a.depth_m.at<float>(200, 300) = 0.0f;
  EXPECT_EQ(PredictKeypoint(key, pair.a, pair.b, 0.03).status, PredictionStatus::kNoDepth);
}

TEST(Correspondence, TurnAboutTheOpticalAxisTurnsTheAngle) {
  const double turn_rad = 30.0 * kPi / 180.0;
  const PlanePair pair =
      MakePlanePair(Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(turn_rad, Eigen::Vector3d::UnitZ())), Eigen::Vector3d::Zero()));
  for (float angle : {0.0f, 45.0f, 100.0f, 350.0f}) {
    const PredictedKeypoint p = PredictKeypoint(Key(360.4f, 250.3f, 10, angle), pair.a, pair.b, 0.03);
    ASSERT_EQ(p.status, PredictionStatus::kVisible);
    // The camera turns by +30 degrees about z: the image content by -30 degrees.
    EXPECT_NEAR(AngleDifferenceDeg(p.angle_in_b_deg, angle - 30.0), 0.0, 0.05) << angle;
    EXPECT_NEAR(p.size_in_b, 10.0, 1e-6);
    // The point turns about the principal point by the same angle.
    const double c = std::cos(-turn_rad), s = std::sin(-turn_rad);
    EXPECT_NEAR(p.pt_in_b.x, 319.5 + c * (360.4 - 319.5) - s * (250.3 - 239.5), 1e-3);
    EXPECT_NEAR(p.pt_in_b.y, 239.5 + s * (360.4 - 319.5) + c * (250.3 - 239.5), 1e-3);
  }
}

TEST(Correspondence, MoveAlongTheOpticalAxisScalesTheSize) {
  const PlanePair pair = MakePlanePair(Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 1.0)));
  const PredictedKeypoint p = PredictKeypoint(Key(400.0f, 300.0f, 6, 70), pair.a, pair.b, 0.03);
  ASSERT_EQ(p.status, PredictionStatus::kVisible);
  EXPECT_NEAR(p.size_in_b, 6.0 * 3.0 / 2.0, 1e-6);   // 3 m away in A, 2 m in B
  EXPECT_NEAR(p.angle_in_b_deg, 70.0, 0.05);          // a zoom keeps directions
  EXPECT_NEAR(p.pt_in_b.x, 319.5 + (400.0 - 319.5) * 1.5, 1e-3);
  EXPECT_NEAR(p.pt_in_b.y, 239.5 + (300.0 - 239.5) * 1.5, 1e-3);
}

TEST(Correspondence, MatchesTheNearestKeypointThatPassesScaleAndAngle) {
  const PlanePair pair = MakePlanePair(Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, 0, 0)));
  const std::vector<cv::KeyPoint> a = {Key(200, 200, 8, 10), Key(400, 300, 8, 10), Key(300, 100, 8, 10),
                                       Key(500, 400, 8, 10), Key(201, 200, 8, 10)};
  std::vector<cv::KeyPoint> b;
  std::vector<cv::Point2f> at;
  for (const cv::KeyPoint& k : a) at.push_back(PredictKeypoint(k, pair.a, pair.b, 0.03).pt_in_b);
  b.push_back(Key(at[0].x - 0.3f, at[0].y, 8, 12));   // 0: matches a[0] (and is a[4]'s nearest too)
  b.push_back(Key(at[1].x + 1.0f, at[1].y, 8, 50));   // 1: angle 40 degrees off
  b.push_back(Key(at[1].x, at[1].y + 1.5f, 12, 10));  // 2: size 1.5 x the predicted
  b.push_back(Key(at[2].x + 2.5f, at[2].y, 8, 10));   // 3: 2.5 px away
  b.push_back(Key(at[3].x - 1.0f, at[3].y, 10, 35));  // 4: within all three tolerances
  const std::vector<KeypointMatch> matches = MatchKeypoints(a, pair.a, b, pair.b, CorrespondenceOptions());
  ASSERT_EQ(matches.size(), 2u);
  EXPECT_EQ(matches[0].index_a, 0);  // a[4] is 1 px farther from b[0]: b[0] stays a[0]'s
  EXPECT_EQ(matches[0].index_b, 0);
  EXPECT_EQ(matches[1].index_a, 3);
  EXPECT_EQ(matches[1].index_b, 4);
  EXPECT_NEAR(matches[1].point_in_world.z(), 3.0f, 1e-5f);
}

TEST(Correspondence, OptionsCheckNamesTheField) {
  CorrespondenceOptions options;
  options.max_scale_ratio = 0.9;
  try {
    options.Check();
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("max_scale_ratio"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace duskmap
