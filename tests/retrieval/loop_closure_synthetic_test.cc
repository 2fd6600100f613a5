// Loop closure detection on a rendered synthetic session (issue 5, "on the
// synthetic dataset: revisits of the start picture at the end of a session
// are detected"). The whole patrol route of one session is rendered at
// 320x240 in daylight; features are extracted from the images, and every
// frame is mapped with AddAndDetect. Ground truth decides what a true loop is.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/random.h"
#include "slam/features/feature_factory.h"
#include "slam/features/feature_options.h"
#include "slam/retrieval/loop_closure_detector.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/scene/scene.h"
#include "slam/synthetic/sensor/route.h"
#include "slam/synthetic/session_simulator.h"

namespace duskmap {
namespace {

struct MappedFrame {
  Rigid3d world_from_camera;
  cv::Mat depth_m;  // the sensor's depth (0 = none)
  PinholeCamera camera;
  LcdResult result;
};

// Fraction of a's pixels with depth (on an 8 px grid) whose surface point is
// seen by b too: inside b's image, in front of it, and not hidden (b's depth
// there within 10 cm + 5 %). Ground truth for "the two frames show the same
// picture".
double ViewOverlap(const MappedFrame& a, const MappedFrame& b) {
  const Rigid3d b_from_a = b.world_from_camera.Inverse() * a.world_from_camera;
  int with_depth = 0, seen = 0;
  for (int v = 4; v < a.depth_m.rows; v += 8) {
    for (int u = 4; u < a.depth_m.cols; u += 8) {
      const float d = a.depth_m.at<float>(v, u);
      if (!(d > 0.0f)) continue;
      ++with_depth;
      const Eigen::Vector3d p = b_from_a * a.camera.Unproject(u, v, d);
      Eigen::Vector2d px;
      if (p.z() <= 0.0 || !b.camera.Project(p, &px) || !b.camera.InImage(px.x(), px.y())) continue;
      const float db = b.depth_m.at<float>(static_cast<int>(px.y()), static_cast<int>(px.x()));
      if (db > 0.0f && std::abs(db - p.z()) < 0.1 + 0.05 * p.z()) ++seen;
    }
  }
  return with_depth == 0 ? 0.0 : static_cast<double>(seen) / with_depth;
}

// Distance and angle between the optical axes of two camera poses.
double PositionErrorM(const Rigid3d& a, const Rigid3d& b) {
  return (a.translation - b.translation).norm();
}
double AxisAngleDeg(const Rigid3d& a, const Rigid3d& b) {
  const Eigen::Vector3d za = a.rotation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d zb = b.rotation * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(za.dot(zb), -1.0, 1.0)) * 180.0 / M_PI;
}
// Close together, looking the same way (the start picture).
bool SamePlace(const Rigid3d& a, const Rigid3d& b) {
  return PositionErrorM(a, b) < 1.0 && AxisAngleDeg(a, b) < 45.0;
}

// Renders the default session 1 route (16:46, sun in the windows) at
// 320x240 on the flat scene and maps it frame by frame.
std::vector<MappedFrame> MapSyntheticSession(const std::string& feature_type) {
  GeneratorConfig config;  // the box apartment without motion blur
  ApplyGeneratorModel("boxes-2026-12-02", &config);
  config.camera.exposure.motion_blur_scale = 0.0;
  config.camera.width = 320;
  config.camera.height = 240;
  config.camera.fx = config.camera.fy = 262.5;  // the 640x480 field of view
  config.lighting.light_texel_m = 0.1;          // coarser light map: faster preparation
  ApartmentOptions scene_options = config.scene;
  scene_options.seed = DeriveSeed(config.seed, 1);
  // The flat scene, on which the bounds below were measured: this is a guard
  // of the LCD code on a fixed input. On the default scene with material
  // relief LCD alone accepts more look-alike views (SURF 20 false of 41,
  // docs/loop_closure.md), which registration rejects in the engine.
  scene_options.relief_scale = 0.0;
  const Scene scene = BuildApartment(scene_options);
  const uint64_t seed = DeriveSeed(config.seed, 100);
  const std::vector<TimedPose> route =
      GenerateRoute(config.route, ApartmentPatrolRoute(), DeriveSeed(seed, 10));
  SessionSimulator simulator(config, scene, 16.0 + 46.0 / 60.0, DeriveSeed(seed, 12));
  simulator.Settle(route.front().world_from_camera, 12);
  FeatureOptions feature_options;
  feature_options.type = feature_type;
  const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(feature_options);
  LoopClosureDetector lcd{LoopClosureOptions()};
  std::vector<MappedFrame> frames;
  for (size_t k = 0; k < route.size(); ++k) {
    const RgbdFrame frame = simulator.Capture(route[k].world_from_camera);
    const NodeId node = static_cast<NodeId>(k + 1);
    MappedFrame mapped;
    mapped.world_from_camera = route[k].world_from_camera;
    mapped.depth_m = frame.depth_m;
    mapped.camera = frame.camera;
    mapped.result = lcd.AddAndDetect(node, 0, extractor->Extract(frame.bgr));
    if (k > 0) lcd.graph().AddLink(node - 1, node, LinkType::kOdometry);
    frames.push_back(std::move(mapped));
  }
  return frames;
}

class LcdSyntheticTest : public ::testing::TestWithParam<const char*> {};

TEST_P(LcdSyntheticTest, RevisitOfTheStartPictureAtTheEndOfTheSessionIsDetected) {
  const std::vector<MappedFrame> frames = MapSyntheticSession(GetParam());
  const int n = static_cast<int>(frames.size());
  ASSERT_GT(n, 100);
  const Rigid3d& start = frames.front().world_from_camera;
  // The start picture: the first frames (standing at the docking view).
  int start_frames = 0;
  while (start_frames < n && SamePlace(frames[start_frames].world_from_camera, start)) ++start_frames;
  ASSERT_GE(start_frames, 2);
  // The revisit: the last frames of the route that see the start picture again.
  int revisit_begin = n;
  while (revisit_begin > n / 2 && SamePlace(frames[revisit_begin - 1].world_from_camera, start)) --revisit_begin;
  ASSERT_LT(revisit_begin, n) << "the route does not end at its start";

  int revisit_detections = 0, revisit_accepted = 0, revisit_same_view = 0;
  int accepted = 0, false_loops = 0;
  for (int k = 0; k < n; ++k) {
    const LcdResult& r = frames[k].result;
    if (!r.accepted()) continue;
    const int h = static_cast<int>(r.hypothesis) - 1;
    ASSERT_GE(h, 0);
    ASSERT_LT(h, k);
    const double overlap = ViewOverlap(frames[k], frames[h]);
    std::cout << "[ measured ] frame " << k << " -> frame " << h << ", score " << r.score
              << ", view overlap " << overlap << "\n";
    if (k >= revisit_begin) {
      // At the revisit the loops found show the same surfaces, and the start
      // picture is found.
      ++revisit_accepted;
      if (overlap >= 0.2) ++revisit_same_view;
      if (h < start_frames) ++revisit_detections;
    }
    // Elsewhere (the filter's start-up excepted: the first 16 frames after
    // the first candidates, see docs/loop_closure.md) an accepted loop must
    // show the same surfaces (e.g. the end of an in-place spin seeing its
    // beginning, or the walk back past the first room).
    if (k >= 26) {
      ++accepted;
      if (overlap < 0.2) {
        ++false_loops;
        std::cout << "[ measured ] false loop: frame " << k << " -> frame " << h << " ("
                  << PositionErrorM(frames[k].world_from_camera, frames[h].world_from_camera) << " m, "
                  << AxisAngleDeg(frames[k].world_from_camera, frames[h].world_from_camera)
                  << " deg apart)\n";
      }
    }
  }
  EXPECT_GE(revisit_detections, 1) << "frames " << revisit_begin << ".." << n - 1
                                   << " revisit frames 0.." << start_frames - 1;
  // The Bayes filter spreads the posterior over graph neighbours: a neighbour
  // of the right place inside an in-place spin can win a frame while looking
  // elsewhere (measured: 1 of the revisit's loops, SURF). Registration
  // rejects those; LCD must be right at the revisit at least 4 times in 5.
  EXPECT_GE(5 * revisit_same_view, 4 * revisit_accepted)
      << revisit_same_view << " of " << revisit_accepted << " revisit loops show the same view";
  // Measured (docs/loop_closure.md): SURF 15 false of 31 accepted (15 of 41
  // with the SURF of before 2026-12-06, which was not OpenCV's), ORB 0 of 4.
  // LCD alone at Rtabmap/LoopThr 0.11 accepts some look-alike rooms (most
  // scores below 0.16); registration must reject those, as in the reference.
  // At most half of LCD's own acceptances may be false.
  EXPECT_LE(2 * false_loops, accepted) << false_loops << " false of " << accepted << " accepted loops";
}

INSTANTIATE_TEST_SUITE_P(Features, LcdSyntheticTest, ::testing::Values("surf", "orb"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace duskmap
