#include "slam/synthetic/scene/relief.h"

#include <gtest/gtest.h>

#include "slam/synthetic/scene/scene_builder.h"
#include "slam/synthetic/scene/textures.h"

namespace duskmap {
namespace {

bool SameBytes(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(ReliefSlopes, APlaneHasItsSlopesEverywhereBordersIncluded) {
  const double texel_x = 0.004, texel_y = 0.01;
  cv::Mat height(7, 9, CV_32F);
  for (int r = 0; r < height.rows; ++r) {
    for (int c = 0; c < height.cols; ++c) height.at<float>(r, c) = static_cast<float>(0.3 * c * texel_x - 0.1 * r * texel_y);
  }
  const cv::Mat slopes = ReliefSlopes(height, texel_x, texel_y);
  ASSERT_EQ(slopes.type(), CV_32FC2);
  ASSERT_EQ(slopes.size(), height.size());
  for (int r = 0; r < slopes.rows; ++r) {
    for (int c = 0; c < slopes.cols; ++c) {
      EXPECT_NEAR(slopes.at<cv::Vec2f>(r, c)[0], 0.3, 1e-4) << r << "," << c;
      EXPECT_NEAR(slopes.at<cv::Vec2f>(r, c)[1], -0.1, 1e-4) << r << "," << c;
    }
  }
}

TEST(ReliefCanvas, DrawsGroovesAndRectanglesAndADisabledOneDrawsNothing) {
  ReliefCanvas canvas(cv::Size(10, 6), 0.01);
  canvas.GrooveColumn(4, 0.002);
  canvas.AddRect(cv::Rect(8, 0, 5, 2), 0.001);  // clipped at the border
  const cv::Mat& h = canvas.height_m();
  EXPECT_FLOAT_EQ(h.at<float>(3, 4), -0.002f);
  EXPECT_FLOAT_EQ(h.at<float>(3, 3), -0.0008f);
  EXPECT_FLOAT_EQ(h.at<float>(3, 5), -0.0008f);
  EXPECT_FLOAT_EQ(h.at<float>(3, 7), 0.0f);
  EXPECT_FLOAT_EQ(h.at<float>(1, 9), 0.001f);
  EXPECT_FLOAT_EQ(h.at<float>(2, 9), 0.0f);
  ReliefCanvas off;
  EXPECT_FALSE(off.enabled());
  off.GrooveRow(1, 0.01);
  off.AddRect(cv::Rect(0, 0, 3, 3), 1.0);
  EXPECT_TRUE(off.height_m().empty());
}

TEST(MakeTexture, ReliefLeavesTheAlbedoAloneAndScalesLinearly) {
  for (const TextureKind kind : {TextureKind::kPaint, TextureKind::kWoodFloor, TextureKind::kTiles,
                                 TextureKind::kFabric, TextureKind::kBooks, TextureKind::kCabinet,
                                 TextureKind::kRadiator, TextureKind::kCurtain, TextureKind::kDoor}) {
    TextureRequest request;
    request.kind = kind;
    request.size_u_m = 0.9;
    request.size_v_m = 0.7;
    request.seed = 42;
    const SurfaceTexture flat = MakeTexture(request, {});
    request.relief_scale = 1.0;
    const SurfaceTexture one = MakeTexture(request, {});
    request.relief_scale = 2.0;
    const SurfaceTexture two = MakeTexture(request, {});
    SCOPED_TRACE(static_cast<int>(kind));
    EXPECT_TRUE(flat.height_m.empty());
    EXPECT_TRUE(SameBytes(flat.albedo, one.albedo));  // the relief draws from its own stream
    ASSERT_EQ(one.height_m.size(), one.albedo.size());
    double lo = 0, hi = 0;
    cv::minMaxLoc(one.height_m, &lo, &hi);
    EXPECT_GT(hi - lo, 1e-4);  // some relief
    EXPECT_LT(hi - lo, 0.2);   // millimetres to centimetres, not decimetres
    EXPECT_LT(cv::norm(two.height_m, one.height_m * 2.0, cv::NORM_INF), 1e-7);
  }
}

TEST(MakeTexture, PrintsAndGlassAreFlat) {
  for (const TextureKind kind : {TextureKind::kPicture, TextureKind::kPoster, TextureKind::kDocking,
                                 TextureKind::kWindow, TextureKind::kScreen, TextureKind::kPackaging}) {
    TextureRequest request;
    request.kind = kind;
    request.relief_scale = 1.0;
    EXPECT_TRUE(MakeTexture(request, {}).height_m.empty()) << static_cast<int>(kind);
  }
}

// The relief follows the structure the albedo draws: a radiator's troughs lie
// on its dark fin lines, a curtain's folds on its fold shading.
TEST(MakeTexture, ReliefFollowsTheDrawnStructure) {
  TextureRequest request;
  request.kind = TextureKind::kRadiator;
  request.size_u_m = 0.6;
  request.size_v_m = 0.5;
  request.relief_scale = 1.0;
  const SurfaceTexture radiator = MakeTexture(request, {});
  const int row = radiator.albedo.rows / 2;
  for (int x = 18; x + 6 < radiator.albedo.cols; x += 12) {  // dark lines at 6 + 12 k
    EXPECT_NEAR(radiator.height_m.at<float>(row, x), 0.0f, 1e-6f) << x;
    EXPECT_GT(radiator.height_m.at<float>(row, x + 6), 0.02f) << x;
    EXPECT_LT(cv::sum(radiator.albedo.at<cv::Vec3f>(row, x))[0],
              cv::sum(radiator.albedo.at<cv::Vec3f>(row, x + 6))[0]) << x;
  }
}

TEST(SceneBuilder, QuadsCarryTheirReliefSlopesAtTheAlbedoSize) {
  SceneBuilder flat(7, {}, 2.5, 0.0), relief(7, {}, 2.5, 1.0);
  const Eigen::Vector3d o(0, 0, 0), u(1, 0, 0), v(0, 0, 1);
  const int a = flat.AddQuad(o, u, v, 1.2, 0.8, 0, TextureKind::kCurtain, {0.5f, 0.5f, 0.5f});
  const int b = relief.AddQuad(o, u, v, 1.2, 0.8, 0, TextureKind::kCurtain, {0.5f, 0.5f, 0.5f});
  const Quad& qa = flat.scene().quads[a];
  const Quad& qb = relief.scene().quads[b];
  EXPECT_TRUE(qa.relief_slope.empty());
  EXPECT_TRUE(SameBytes(qa.albedo, qb.albedo));
  ASSERT_EQ(qb.relief_slope.size(), qb.albedo.size());
  // Curtain folds: slopes along u of up to 2 pi x 50 mm / 0.21 m, none along v.
  double lo = 0, hi = 0;
  cv::Mat channels[2];
  cv::split(qb.relief_slope, channels);
  cv::minMaxLoc(channels[0], &lo, &hi);
  EXPECT_GT(hi, 1.0);
  EXPECT_LT(lo, -1.0);
  EXPECT_LT(cv::norm(channels[1], cv::NORM_INF), 0.5);  // only the weave
  const int c = relief.AddQuad(o, u, v, 0.3, 0.3, 0, TextureKind::kPicture, {0.5f, 0.5f, 0.5f});
  EXPECT_TRUE(relief.scene().quads[c].relief_slope.empty());
}

}  // namespace
}  // namespace duskmap
