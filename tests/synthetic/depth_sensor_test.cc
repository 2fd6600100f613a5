#include "slam/synthetic/sensor/depth_sensor.h"

#include "slam/core/check.h"

#include <gtest/gtest.h>

#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/apartment.h"

namespace duskmap {
namespace {

TEST(SimulateDepth, NoDepthThroughGlassBeyondRangeOrAtGrazingAngles) {
  const Scene scene = BuildApartment(ApartmentOptions());
  LightingOptions lighting;
  lighting.light_texel_m = 0.25;
  const std::vector<cv::Mat> radiance = PrepareRadiance(scene, ComputeSessionLighting(lighting, scene, 17.0), lighting);
  PinholeCamera camera;
  camera.width = 160;
  camera.height = 120;
  camera.fx = camera.fy = 131.25;
  camera.cx = 79.5;
  camera.cy = 59.5;
  const Renderer renderer(scene, camera);
  RenderedView view;
  // Living room, facing the west windows from 3 m away.
  renderer.Render(radiance, Rigid3d(CameraRotationFromYawPitchRoll(M_PI, 0.0, 0.0), Eigen::Vector3d(3.0, 2.3, 1.5)), &view);
  DepthSensorOptions options;
  SensorNoise noise(1);
  const cv::Mat depth = SimulateDepth(options, scene, view, noise);
  int glass = 0, valid = 0;
  double max_error = 0.0;
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const int id = view.surface_id.at<int>(v, u);
      const float d = depth.at<float>(v, u);
      if (id >= 0 && scene.quads[id].emission == Emission::kSky) {
        ++glass;
        EXPECT_EQ(d, 0.0f);
      }
      if (d > 0.0f) {
        ++valid;
        const double z = view.depth_m.at<float>(v, u);
        EXPECT_LE(z, options.max_range_m);
        EXPECT_GE(view.cos_incidence.at<float>(v, u), options.min_cos_incidence);
        max_error = std::max(max_error, std::abs(d - z) / (options.noise_base_m + options.noise_quadratic * (z - 0.4) * (z - 0.4)));
      }
    }
  }
  EXPECT_GT(glass, 500);
  EXPECT_GT(valid, 5000);
  EXPECT_LT(max_error, 6.0);  // within 6 sigma of the noise model
}

TEST(DepthSensorOptions, CheckNamesTheField) {
  DepthSensorOptions o;
  o.max_range_m = 0.1;
  EXPECT_THROW(o.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
