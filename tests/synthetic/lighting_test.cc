#include "slam/synthetic/light/lighting.h"

#include <cmath>

#include <gtest/gtest.h>

#include "one_window_scene.h"
#include "slam/core/check.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/render/renderer.h"
#include "slam/synthetic/scene/apartment.h"
#include "small_camera.h"

namespace duskmap {
namespace {

class LightingTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(BuildApartment(ApartmentOptions())); }
  static void TearDownTestSuite() { delete scene_; }
  static Scene* scene_;
  LightingOptions options_;
};
Scene* LightingTest::scene_ = nullptr;

std::vector<double> SortedDefaultTimes() {
  std::vector<double> times;
  for (const SessionSpec& s : GeneratorConfig::DefaultSessions()) times.push_back(ParseClockTime(s.clock_time, s.name));
  std::sort(times.begin(), times.end());
  return times;
}

TEST_F(LightingTest, WindowLitIrradianceFallsAcrossSessionTimes) {
  // Living-room ceiling next to the west windows and the east wall facing them.
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> probes = {
      {{0.8, 2.3, 2.499}, {0, 0, -1}}, {{5.999, 0.6, 1.2}, {-1, 0, 0}}};
  for (const auto& [point, normal] : probes) {
    double previous = 1e30;
    for (double t : SortedDefaultTimes()) {
      const SessionLighting l = ComputeSessionLighting(options_, *scene_, t);
      const IrradianceParts e = ComputeDirectIrradiance(*scene_, l, point, normal, 0, -1);
      const double daylight = Luminance(e.sun + e.sky);
      EXPECT_LT(daylight, previous) << "at " << t << " h, probe " << point.transpose();
      previous = daylight;
    }
  }
}

TEST_F(LightingTest, SunPatchesEnterThroughTheWindowsInTheAfternoon) {
  const SessionLighting l = ComputeSessionLighting(options_, *scene_, 16.0 + 46.0 / 60);
  ASSERT_GT(l.sun_normal_lux_bgr[1], 0.0f);
  int sunlit = 0;
  for (double x = 0.1; x < 6.0; x += 0.1) {
    for (double y = 0.1; y < 4.6; y += 0.1) {
      sunlit += Luminance(ComputeDirectIrradiance(*scene_, l, {x, y, 0.001}, {0, 0, 1}, 0, -1).sun) > 0.0f;
    }
  }
  EXPECT_GT(sunlit, 20);    // a patch on the floor
  EXPECT_LT(sunlit, 1500);  // not the whole floor
}

TEST_F(LightingTest, AfterDuskOnlyTheLampsLight) {
  const SessionLighting l = ComputeSessionLighting(options_, *scene_, 20.75);
  EXPECT_LT(l.sun.elevation_deg, -6.0);
  // A living-room floor point the floor lamp reaches, and a bedroom wall
  // point above the bed that the bedside lamp reaches (lamps cast shadows:
  // the bed hides that lamp from most of the bedroom floor).
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> points[] = {
      {{1.0, 2.0, 0.001}, {0, 0, 1}}, {{3.5, 6.02, 1.0}, {0, 1, 0}}};
  for (const auto& [point, normal] : points) {
    const int room = point.y() < 4.6 ? 0 : 3;
    const IrradianceParts e = ComputeDirectIrradiance(*scene_, l, point, normal, room, -1);
    EXPECT_EQ(Luminance(e.sun), 0.0f);
    EXPECT_GT(Luminance(e.lamps), 0.0f);
    EXPECT_LT(Luminance(e.sky), 0.01f * Luminance(e.lamps));
  }
}

TEST_F(LightingTest, LampsCastShadows) {
  // At night the bedside lamp (0.75 m high, beside the bed) lights the duvet
  // but not the floor on the far side of the bed.
  const SessionLighting l = ComputeSessionLighting(options_, *scene_, 20.75);
  const int bedroom = 3;
  const IrradianceParts on_bed =
      ComputeDirectIrradiance(*scene_, l, {3.0, 7.5, 0.56}, {0, 0, 1}, bedroom, -1);
  const IrradianceParts behind_bed =
      ComputeDirectIrradiance(*scene_, l, {1.2, 7.0, 0.001}, {0, 0, 1}, bedroom, -1);
  EXPECT_GT(Luminance(on_bed.lamps), 1.0f);
  EXPECT_EQ(Luminance(behind_bed.lamps), 0.0f);
}

// The optional bedroom ceiling light (off by default; docs/synthetic_dataset.md,
// "What was tried") lights the floor behind the bed that the bedside lamp
// cannot reach, and is on in every session.
TEST_F(LightingTest, OptionalBedroomCeilingLightReachesBehindTheBed) {
  ApartmentOptions options;
  options.lamps.bedroom_ceiling_cd = 70.0;
  const Scene lit = BuildApartment(options);
  ASSERT_EQ(lit.lamps.size(), scene_->lamps.size() + 1);
  const SessionLighting l = ComputeSessionLighting(options_, lit, 20.75);
  EXPECT_TRUE(l.lamp_on.back());
  const IrradianceParts behind_bed =
      ComputeDirectIrradiance(lit, l, {1.2, 7.0, 0.001}, {0, 0, 1}, 3, -1);
  EXPECT_GT(Luminance(behind_bed.lamps), 1.0f);
  options.lamps.bedroom_ceiling_cd = -1.0;
  EXPECT_THROW(BuildApartment(options), ConfigError);
}

TEST_F(LightingTest, LivingRoomLampSwitchesOnAt1754) {
  int lamp = -1;
  for (size_t i = 0; i < scene_->lamps.size(); ++i) {
    if (scene_->lamps[i].on_from == "17:54") lamp = static_cast<int>(i);
  }
  ASSERT_GE(lamp, 0);
  EXPECT_FALSE(ComputeSessionLighting(options_, *scene_, 17.0 + 53.0 / 60).lamp_on[lamp]);
  EXPECT_TRUE(ComputeSessionLighting(options_, *scene_, 17.0 + 54.0 / 60).lamp_on[lamp]);
  // Every other lamp is on in every session.
  for (double t : SortedDefaultTimes()) {
    const SessionLighting l = ComputeSessionLighting(options_, *scene_, t);
    for (size_t i = 0; i < scene_->lamps.size(); ++i) {
      if (static_cast<int>(i) != lamp) {
        EXPECT_TRUE(l.lamp_on[i]);
      }
    }
  }
  // The lamp raises the irradiance next to it.
  const Eigen::Vector3d near_lamp(5.0, 4.0, 0.001);
  const auto lamps_at = [&](double t) {
    return Luminance(ComputeDirectIrradiance(*scene_, ComputeSessionLighting(options_, *scene_, t), near_lamp,
                                             {0, 0, 1}, 0, -1).lamps);
  };
  EXPECT_GT(lamps_at(17.95), lamps_at(17.85) + 1.0f);
}

// The irradiance vector's component along the normal is the irradiance
// itself, whatever lights the point: sun and sky by day, lamps at night.
TEST_F(LightingTest, IrradianceVectorAlongTheNormalIsTheIrradiance) {
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> probes = {
      {{0.8, 2.3, 2.499}, {0, 0, -1}}, {{5.999, 0.6, 1.2}, {-1, 0, 0}}, {{2.0, 2.0, 0.001}, {0, 0, 1}},
      {{1.0, 1.0, 0.001}, {0, 0, 1}}, {{3.0, 4.59, 1.5}, {0, -1, 0}}};
  int sunlit = 0;
  for (const double t : {16.0 + 46.0 / 60, 18.5, 20.75}) {
    const SessionLighting l = ComputeSessionLighting(options_, *scene_, t);
    for (const auto& [point, normal] : probes) {
      const IrradianceParts e = ComputeDirectIrradiance(*scene_, l, point, normal, 0, -1);
      sunlit += Luminance(e.sun) > 0.0f;
      const double along_normal = e.direction_weighted.dot(normal);
      EXPECT_NEAR(along_normal, Luminance(e.total()), 1e-4 * Luminance(e.total()) + 1e-9)
          << "at " << t << " h, probe " << point.transpose();
    }
  }
  EXPECT_GT(sunlit, 0);  // the sun term is covered too
}

// A one-quad room lit by one lamp: the irradiance vector points at the lamp
// with the lamp's I / r^2, and a relief slope tilting a texel's normal
// towards the lamp brightens it by exactly the cosine it gains (ambient off).
TEST(PrepareRadiance, ReliefShadesByTheDirectionTheLightComesFrom) {
  Scene scene;
  scene.room_names = {"test room"};
  Quad floor;
  floor.origin_in_world = Eigen::Vector3d(0, 0, 0);
  floor.u_axis = Eigen::Vector3d::UnitX();
  floor.v_axis = Eigen::Vector3d::UnitY();
  floor.size_u_m = floor.size_v_m = 1.0;
  floor.albedo = cv::Mat(40, 40, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
  scene.quads.push_back(floor);
  Lamp lamp;
  lamp.name = "test lamp";
  lamp.position_in_world = Eigen::Vector3d(1.5, 0.5, 1.0);
  lamp.intensity_cd = 100.0;
  scene.lamps.push_back(lamp);
  LightingOptions options;
  options.ambient_fraction = 0.0;
  options.ambient_leak = 0.0;
  options.light_texel_m = 0.025;
  const SessionLighting l = ComputeSessionLighting(options, scene, 20.75);
  const Eigen::Vector3d centre(0.5125, 0.5125, 0.0);  // texel (20, 20)
  const Eigen::Vector3d to_lamp = lamp.position_in_world - centre;
  const double r2 = to_lamp.squaredNorm();
  const IrradianceParts e = ComputeDirectIrradiance(scene, l, centre, Eigen::Vector3d::UnitZ(), 0, 0);
  EXPECT_LT((e.direction_weighted - lamp.intensity_cd / r2 * to_lamp.normalized()).norm(), 1e-6 * lamp.intensity_cd / r2);

  const auto radiance_at_centre = [&](float slope_u) {
    scene.quads[0].relief_slope = cv::Mat(40, 40, CV_32FC2, cv::Scalar(slope_u, 0.0));
    const std::vector<cv::Mat> radiance = PrepareRadiance(scene, l, options);
    return static_cast<double>(Luminance(radiance[0].at<cv::Vec3f>(20, 20)));
  };
  const double flat = radiance_at_centre(0.0f);
  EXPECT_NEAR(flat, 0.5 * lamp.intensity_cd * to_lamp.normalized().z() / r2 / M_PI, 0.01 * flat);
  for (const float slope : {-0.3f, 0.3f}) {
    // n' = (-slope, 0, 1) / |.|: a negative slope along x tilts towards the lamp at larger x.
    const Eigen::Vector3d tilted = Eigen::Vector3d(-slope, 0.0, 1.0).normalized();
    const double expected = flat * tilted.dot(to_lamp.normalized()) / to_lamp.normalized().z();
    EXPECT_NEAR(radiance_at_centre(slope), expected, 0.01 * expected) << slope;
  }
  EXPECT_GT(radiance_at_centre(-0.3f), 1.2 * flat);
  EXPECT_LT(radiance_at_centre(0.3f), 0.8 * flat);
  // A slope steep enough to face away from the lamp receives none of it.
  EXPECT_EQ(radiance_at_centre(5.0f), 0.0);
}

TEST(ColorTemperatureToBgr, WarmLightIsRedderThanDaylight) {
  const cv::Vec3f warm = ColorTemperatureToBgr(2700), day = ColorTemperatureToBgr(6500);
  EXPECT_GT(warm[2] / warm[0], 2.0f);
  EXPECT_NEAR(day[2] / day[0], 1.0f, 1e-4f);
  EXPECT_NEAR(Luminance(warm), 1.0f, 1e-5f);
}

TEST(ParseClockTime, RejectsMalformed) {
  EXPECT_DOUBLE_EQ(ParseClockTime("17:54", "t"), 17.9);
  EXPECT_THROW(ParseClockTime("5:54", "t"), ConfigError);
  EXPECT_THROW(ParseClockTime("25:00", "t"), ConfigError);
  EXPECT_THROW(ParseClockTime("17:5x", "t"), ConfigError);
}

TEST(LightingOptions, TheHorizonIsAnElevationABuildingCouldHave) {
  LightingOptions options;
  options.horizon_elevation_deg = 14.0;
  EXPECT_NO_THROW(options.Check());
  for (const double bad : {-6.0, 46.0, std::nan("")}) {
    options.horizon_elevation_deg = bad;
    EXPECT_THROW(options.Check(), ConfigError) << bad;
  }
}

// Brute force over the window: each element's radiance is decided by the
// elevation of the direction from the point through it.
double IntegrateWindow(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double facade_top_deg,
                       double sky, double facade, double ground) {
  constexpr int kU = 400, kV = 240;
  double sum = 0.0;
  for (int i = 0; i < kU; ++i) {
    for (int j = 0; j < kV; ++j) {
      const Eigen::Vector3d w(0.0, -1.0 + 2.0 * (i + 0.5) / kU, 0.9 + 1.2 * (j + 0.5) / kV);
      const Eigen::Vector3d d = w - point;
      const double r = d.norm();
      const double cos_receiver = normal.dot(d) / r;
      if (cos_receiver <= 0.0) continue;
      const double elevation_deg = std::asin(d.z() / r) * 180.0 / M_PI;
      const double radiance = elevation_deg > facade_top_deg ? sky : elevation_deg > 0.0 ? facade : ground;
      sum += radiance * cos_receiver * (-d.x() / r) / (r * r) * (2.0 / kU) * (1.2 / kV);
    }
  }
  return sum;
}

TEST(WindowView, GroundFacadesAndSkyMatchABruteForceIntegration) {
  const Scene scene = OneWindowScene();
  LightingOptions options;
  options.window_view_obstructed = true;
  options.horizon_elevation_deg = 14.0;
  SessionLighting l = ComputeSessionLighting(options, scene, 20.75);
  l.sun_normal_lux_bgr = cv::Vec3f(0, 0, 0);
  l.sky_nits_bgr = cv::Vec3f(1000, 1000, 1000);
  l.shaded_facade_nits_bgr = cv::Vec3f(150, 150, 150);
  l.ground_nits_bgr = cv::Vec3f(200, 200, 200);
  SessionLighting open = l;
  open.window_view_obstructed = false;
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> probes = {
      {{4.0, 0.0, 1.4}, {-1, 0, 0}},   // the far wall at eye height
      {{3.0, 0.8, 1.3}, {0, -1, 0}},   // a side wall
      {{2.0, -0.5, 0.75}, {0, 0, 1}},  // a table
      {{2.0, 0.0, 2.5}, {0, 0, -1}},   // the ceiling
      {{1.2, 0.3, 0.0}, {0, 0, 1}}};   // the floor near the window
  for (const auto& [point, normal] : probes) {
    const double split = Luminance(ComputeDirectIrradiance(scene, l, point, normal, 0, -1).sky);
    const double expected = IntegrateWindow(point, normal, 14.0, 1000, 150, 200);
    EXPECT_NEAR(split, expected, 0.03 * expected) << point.transpose();
    const double uniform = Luminance(ComputeDirectIrradiance(scene, open, point, normal, 0, -1).sky);
    EXPECT_NEAR(uniform, IntegrateWindow(point, normal, 14.0, 1000, 1000, 1000), 0.01 * uniform);
  }
  // Eye height sees facades and ground, far below the sky; the floor near
  // the window sees the sky alone (its whole view lies above 36 degrees).
  const auto ratio = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    return Luminance(ComputeDirectIrradiance(scene, l, p, n, 0, -1).sky) /
           Luminance(ComputeDirectIrradiance(scene, open, p, n, 0, -1).sky);
  };
  EXPECT_LT(ratio({4.0, 0.0, 1.4}, {-1, 0, 0}), 0.3);
  EXPECT_FLOAT_EQ(ratio({1.2, 0.3, 0.0}, {0, 0, 1}), 1.0f);
}

// The sun's visibility a floor texel's radiance shows (sun only, no sky, no
// ambient), by texel.
cv::Mat SunFractionOnFloor(const cv::Mat& radiance, double cos_sun, double sun_lux) {
  std::vector<cv::Mat> channels;
  cv::split(radiance, channels);
  return channels[1] / (0.5 * sun_lux * cos_sun / M_PI);
}

TEST(PrepareSessionRadiance, TheSunPerTexelDrawsThePatchTheWindowCasts) {
  // OneWindowScene's window (x = 0, y -1..1, z 0.9..2.1) and a floor at 1 cm
  // texels; the sun low in the west-south-west, so the patch's sides slant.
  Scene scene = OneWindowScene();
  Quad floor;
  floor.origin_in_world = Eigen::Vector3d(0.05, -2.2, 0.0);
  floor.u_axis = Eigen::Vector3d::UnitX();
  floor.v_axis = Eigen::Vector3d::UnitY();
  floor.size_u_m = 3.0;
  floor.size_v_m = 3.0;
  floor.albedo = cv::Mat(300, 300, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
  scene.quads.push_back(floor);
  LightingOptions options;
  const SessionLighting l = LowSunAlone(scene, &options);
  const Eigen::Vector3d& to_sun = l.sun_direction_in_world;
  const double cos_sun = to_sun.z();

  options.sun_per_texel = true;
  const cv::Mat per_texel = SunFractionOnFloor(PrepareSessionRadiance(scene, l, options).quads[1], cos_sun, 1000);
  options.sun_per_texel = false;
  const cv::Mat light_map = SunFractionOnFloor(PrepareSessionRadiance(scene, l, options).quads[1], cos_sun, 1000);

  // Where each texel's centre sees the sun through the window, and how far
  // (on the window) from the window's edge.
  double area_m2 = 0.0, texel_error = 0.0, map_error = 0.0;
  int edge_texels = 0;
  for (int r = 0; r < 300; ++r) {
    for (int c = 0; c < 300; ++c) {
      const Eigen::Vector3d p = floor.PointAt((c + 0.5) * 0.01, (r + 0.5) * 0.01);
      const double t = -p.x() / to_sun.x();
      const double y = p.y() + t * to_sun.y(), z = t * to_sun.z();
      const double inside_m = std::min({y + 1.0, 1.0 - y, z - 0.9, 2.1 - z});
      const float expected = inside_m >= 0.0 ? 1.0f : 0.0f;
      const float value = per_texel.at<float>(r, c);
      area_m2 += value * 1e-4;
      if (std::abs(inside_m) > 0.03) {
        ASSERT_NEAR(value, expected, 1e-4) << r << " " << c;
        EXPECT_NEAR(light_map.at<float>(r, c), expected, std::abs(inside_m) > 0.15 ? 1e-4 : 1.0);
      } else {
        texel_error += std::abs(value - expected);
        map_error += std::abs(light_map.at<float>(r, c) - expected);
        ++edge_texels;
      }
    }
  }
  // The window's 2.4 m2 projected along the sun onto the floor.
  EXPECT_NEAR(area_m2, 2.4 * (-to_sun.x()) / to_sun.z(), 0.01 * 3.2);
  ASSERT_GT(edge_texels, 500);
  // Near the edges the texels follow the window's straight edges (off only
  // by the penumbra); the light map's 5 cm nodes draw stairs.
  EXPECT_LT(texel_error, 0.5 * map_error) << texel_error / edge_texels << " against " << map_error / edge_texels;
}

TEST(WindowView, GroundAndFacadesAreLitBySkyAndSun) {
  const Scene scene = OneWindowScene();
  LightingOptions options;
  options.window_view_obstructed = true;
  options.horizon_elevation_deg = 1.5;
  const SessionLighting l = ComputeSessionLighting(options, scene, 16.75);  // sun up, about 24 degrees
  ASSERT_GT(l.sun_normal_lux_bgr[1], 0.0f);
  const double sin_sun = std::sin(l.sun.elevation_deg * M_PI / 180.0);
  EXPECT_NEAR(l.ground_nits_bgr[1], 0.2 * (l.sky_nits_bgr[1] + l.sun_normal_lux_bgr[1] * sin_sun / M_PI),
              1e-3 * l.ground_nits_bgr[1]);
  EXPECT_NEAR(l.shaded_facade_nits_bgr[1], 0.15 * (l.sky_nits_bgr[1] + l.ground_nits_bgr[1]),
              1e-3 * l.shaded_facade_nits_bgr[1]);
  options.window_view_obstructed = false;
  const SessionLighting open = ComputeSessionLighting(options, scene, 16.75);
  EXPECT_EQ(open.ground_nits_bgr, cv::Vec3f(0, 0, 0));
  EXPECT_FALSE(open.window_view_obstructed);
}

TEST(LightingOptions, ReflectancesOutsideZeroToOneAreRefused) {
  LightingOptions options;
  for (const double bad : {-0.1, 1.1}) {
    options.facade_reflectance = bad;
    EXPECT_THROW(options.Check(), ConfigError) << bad;
    options.facade_reflectance = 0.3;
    options.ground_reflectance = bad;
    EXPECT_THROW(options.Check(), ConfigError) << bad;
    options.ground_reflectance = 0.2;
  }
  EXPECT_NO_THROW(options.Check());
}

// The camera sees what the window's light comes from: through the pane, by
// each pixel's elevation, the ground below the horizon, the facades up to
// their top and the sky above (window_view_in_camera); the old behaviour
// (the texture times the sky everywhere) with it off.
TEST(WindowView, TheCameraSeesGroundFacadesAndSkyThroughThePane) {
  const Scene scene = OneWindowScene();
  LightingOptions options;
  options.window_view_obstructed = true;
  options.window_view_in_camera = true;
  options.horizon_elevation_deg = 8.0;
  const SessionLighting l = ComputeSessionLighting(options, scene, 16.75);
  const SessionRadiance radiance = PrepareSessionRadiance(scene, l, options);
  ASSERT_TRUE(radiance.window_view.enabled);
  EXPECT_EQ(radiance.quads[0].at<cv::Vec3f>(3, 3), cv::Vec3f(1, 1, 1));  // a pane mask, not radiance
  const WindowViewRadiance& view = radiance.window_view;
  // The three are different lights, so the rows below tell them apart.
  EXPECT_GT(cv::norm(view.ground_nits_bgr - view.facade_nits_bgr[0]), 0.05 * cv::norm(view.sky_nits_bgr));
  EXPECT_GT(cv::norm(view.sky_nits_bgr - view.facade_nits_bgr[0]), 0.05 * cv::norm(view.sky_nits_bgr));

  // Level, 2 m in front of the window (which spans -16.7 to +16.7 degrees
  // of elevation from here), looking at it along -x.
  const Rigid3d world_from_camera(CameraRotationFromYawPitchRoll(M_PI, 0.0, 0.0), Eigen::Vector3d(2.0, 0.0, 1.5));
  const PinholeCamera camera = SmallCamera();
  const auto row_at = [&](double elevation_deg) {
    return static_cast<int>(std::lround(camera.cy - camera.fy * std::tan(elevation_deg * M_PI / 180.0)));
  };
  const int col = static_cast<int>(camera.cx);
  RenderedView seen;
  Renderer(scene, camera).Render(radiance, world_from_camera, &seen);
  const auto expect_at = [&](double elevation_deg, const cv::Vec3f& nits) {
    const cv::Vec3f v = seen.radiance.at<cv::Vec3f>(row_at(elevation_deg), col);
    EXPECT_EQ(seen.surface_id.at<int>(row_at(elevation_deg), col), 0) << elevation_deg;
    EXPECT_LT(cv::norm(v - nits), 1e-4 * cv::norm(nits)) << elevation_deg << " deg: " << v << " against " << nits;
  };
  expect_at(-8.0, view.ground_nits_bgr);
  expect_at(4.0, view.facade_nits_bgr[0]);
  expect_at(12.0, view.sky_nits_bgr);

  options.window_view_in_camera = false;
  const SessionRadiance open = PrepareSessionRadiance(scene, l, options);
  EXPECT_FALSE(open.window_view.enabled);
  Renderer(scene, camera).Render(open, world_from_camera, &seen);
  for (const double elevation : {-8.0, 4.0, 12.0}) {
    const cv::Vec3f v = seen.radiance.at<cv::Vec3f>(row_at(elevation), col);
    EXPECT_LT(cv::norm(v - l.sky_nits_bgr), 1e-4 * cv::norm(l.sky_nits_bgr)) << elevation;
  }
}

TEST(WindowView, InTheCameraNeedsTheObstructedViewAndNoMirrors) {
  LightingOptions options;
  options.window_view_in_camera = true;
  EXPECT_THROW(options.Check(), ConfigError);
  options.window_view_obstructed = true;
  EXPECT_NO_THROW(options.Check());
  GeneratorConfig config;
  config.lighting = options;
  EXPECT_NO_THROW(config.Check());
  config.scene.window_reflectance = 0.08;
  EXPECT_THROW(config.Check(), ConfigError);
  config.scene.window_reflectance = 0.0;
  config.scene.floor_reflectance = 0.04;
  EXPECT_THROW(config.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
