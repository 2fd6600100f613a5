#include "slam/synthetic/render/renderer.h"

#include <gtest/gtest.h>

#include "small_camera.h"

#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/sensor/route.h"

namespace duskmap {
namespace {

class RendererTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(BuildApartment(ApartmentOptions()));
    LightingOptions options;
    options.light_texel_m = 0.25;
    radiance_ = new std::vector<cv::Mat>(
        PrepareRadiance(*scene_, ComputeSessionLighting(options, *scene_, 17.0), options));
  }
  static void TearDownTestSuite() {
    delete radiance_;
    delete scene_;
  }
  static Scene* scene_;
  static std::vector<cv::Mat>* radiance_;
};
Scene* RendererTest::scene_ = nullptr;
std::vector<cv::Mat>* RendererTest::radiance_ = nullptr;

// Back-projecting a pixel with its depth and ground-truth pose and projecting
// it into another session's frame at the corresponding pose lands on the same
// surface (same quad id, same colour under identical lighting).
TEST_F(RendererTest, BackProjectedPixelsLandOnTheSameSurfaceInAnotherSession) {
  const std::vector<TimedPose> route_a = GenerateRoute(RouteOptions(), ApartmentPatrolRoute(), 1);
  const std::vector<TimedPose> route_b = GenerateRoute(RouteOptions(), ApartmentPatrolRoute(), 2);
  const Renderer renderer(*scene_, SmallCamera());
  int checked = 0, same_surface = 0, same_color = 0;
  for (size_t k = 0; k < route_a.size(); k += 15) {
    const Rigid3d& world_from_a = route_a[k].world_from_camera;
    size_t best = 0;
    for (size_t j = 0; j < route_b.size(); ++j) {
      if ((route_b[j].world_from_camera.translation - world_from_a.translation).norm() <
          (route_b[best].world_from_camera.translation - world_from_a.translation).norm()) {
        best = j;
      }
    }
    const Rigid3d& world_from_b = route_b[best].world_from_camera;
    RenderedView a, b;
    renderer.Render(*radiance_, world_from_a, &a);
    renderer.Render(*radiance_, world_from_b, &b);
    const Rigid3d b_from_a = world_from_b.Inverse() * world_from_a;
    for (int v = 5; v < 120; v += 10) {
      for (int u = 5; u < 160; u += 10) {
        const float depth = a.depth_m.at<float>(v, u);
        if (depth <= 0.0f) continue;
        Eigen::Vector2d pixel;
        const Eigen::Vector3d p_in_b = b_from_a * renderer.camera().Unproject(u, v, depth);
        if (!renderer.camera().Project(p_in_b, &pixel)) continue;
        const int ub = static_cast<int>(std::lround(pixel.x())), vb = static_cast<int>(std::lround(pixel.y()));
        if (ub < 1 || vb < 1 || ub >= 159 || vb >= 119) continue;
        // Skip points hidden in b (something nearer along the ray).
        if (std::abs(b.depth_m.at<float>(vb, ub) - p_in_b.z()) > 0.05) continue;
        ++checked;
        same_surface += a.surface_id.at<int>(v, u) == b.surface_id.at<int>(vb, ub);
        const cv::Vec3f ca = a.radiance.at<cv::Vec3f>(v, u), cb = b.radiance.at<cv::Vec3f>(vb, ub);
        same_color += cv::norm(ca - cb) <= 0.35 * cv::norm(ca) + 1.0;
      }
    }
  }
  ASSERT_GT(checked, 200);
  EXPECT_GT(same_surface, 0.97 * checked);
  EXPECT_GT(same_color, 0.8 * checked);
}

TEST_F(RendererTest, DepthMatchesAKnownWall) {
  // Facing the living-room north wall (y = 4.6) from y = 1.0, level.
  const Rigid3d world_from_camera(CameraRotationFromYawPitchRoll(M_PI / 2, 0.0, 0.0), Eigen::Vector3d(4.0, 1.0, 2.3));
  const Renderer renderer(*scene_, SmallCamera());
  RenderedView view;
  renderer.Render(*radiance_, world_from_camera, &view);
  EXPECT_NEAR(view.depth_m.at<float>(60, 80), 3.6, 1e-3);
  EXPECT_NEAR(view.cos_incidence.at<float>(60, 80), 1.0, 1e-3);
  EXPECT_GE(view.surface_id.at<int>(60, 80), 0);
  const cv::Vec3f c = view.radiance.at<cv::Vec3f>(60, 80);
  EXPECT_GT(c[1], 0.0f);
}

TEST_F(RendererTest, EveryPixelSeesSomethingInsideTheApartment) {
  const Renderer renderer(*scene_, SmallCamera());
  RenderedView view;
  for (const TimedPose& p : GenerateRoute(RouteOptions(), ApartmentPatrolRoute(), 3)) {
    renderer.Render(*radiance_, p.world_from_camera, &view);
    EXPECT_EQ(cv::countNonZero(view.surface_id < 0), 0) << "holes at t=" << p.time_s;
  }
}

Quad FlatQuad(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
              double size_m, Emission emission) {
  Quad q;
  q.origin_in_world = origin;
  q.u_axis = u;
  q.v_axis = v;
  q.size_u_m = q.size_v_m = size_m;
  q.emission = emission;
  q.albedo = cv::Mat(8, 8, CV_32FC3, cv::Scalar(1, 1, 1));
  return q;
}

// A window pane facing the camera 2 m ahead, a green wall 1 m behind the
// camera facing the pane, and a grey wall outside, beyond the pane. The pane
// shows what lies behind it plus, with a mirror reflectance, the green wall
// (Fresnel at normal incidence: the reflectance itself); the outside wall is
// never mirrored and the depth stays the pane's.
TEST(Renderer, AMirrorPaneAddsTheReflectedRoomByItsFresnelReflectance) {
  const Eigen::Vector3d east(1, 0, 0), west(-1, 0, 0), down(0, 0, -1);
  Scene scene;
  scene.room_names = {"room"};
  scene.quads.push_back(FlatQuad({1, 2, 1}, west, down, 2.0, Emission::kSky));    // faces -y
  scene.quads.push_back(FlatQuad({-2, -1, 2}, east, down, 4.0, Emission::kNone));  // faces +y
  scene.quads.push_back(FlatQuad({2, 3, 2}, west, down, 4.0, Emission::kNone));    // outside
  const std::vector<cv::Mat> radiance = {cv::Mat(8, 8, CV_32FC3, cv::Scalar(1, 1, 1)),
                                         cv::Mat(8, 8, CV_32FC3, cv::Scalar(0, 10, 0)),
                                         cv::Mat(8, 8, CV_32FC3, cv::Scalar(5, 5, 5))};
  const Rigid3d world_from_camera(Eigen::Quaterniond(CameraRotationFromYawPitchRoll(M_PI / 2, 0, 0)),
                                  Eigen::Vector3d::Zero());
  const PinholeCamera camera = SmallCamera();
  const int u = 80, v = 60;  // near the centre: normal incidence
  for (double reflectance : {0.0, 0.5}) {
    SCOPED_TRACE(reflectance);
    scene.quads[0].mirror_reflectance = reflectance;
    const Renderer renderer(scene, camera);
    RenderedView view;
    renderer.Render(radiance, world_from_camera, &view);
    ASSERT_EQ(view.surface_id.at<int>(v, u), 0);
    EXPECT_NEAR(view.depth_m.at<float>(v, u), 2.0f, 1e-4f);
    const cv::Vec3f seen = view.radiance.at<cv::Vec3f>(v, u);
    const double cos = view.cos_incidence.at<float>(v, u);
    const double fresnel = reflectance + (1 - reflectance) * std::pow(1 - cos, 5);
    const double expected_green = reflectance > 0 ? (1 - fresnel) * 1 + fresnel * 10 : 1.0;
    const double expected_other = reflectance > 0 ? (1 - fresnel) * 1 : 1.0;
    EXPECT_NEAR(seen[1], expected_green, 1e-3);
    EXPECT_NEAR(seen[0], expected_other, 1e-3);
    EXPECT_NEAR(seen[2], expected_other, 1e-3);
  }
}

}  // namespace
}  // namespace duskmap
