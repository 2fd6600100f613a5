// Transformation estimation on pairs of the synthetic dataset (issue 4: "TE
// on pairs from the synthetic dataset, same place, different sessions and
// times, against ground truth"). The map node is a frame of session 1's route
// (16:46), rendered with depth; the query is the frame at the same index of
// session A's route (another walk of the same route, different offsets),
// rendered once in the same light (16:46) and once at night (session 6's
// 19:35, lamps on, sun set). Rendered in the test at the dataset's 640x480.
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core/utility.hpp>

#include "slam/core/random.h"
#include "slam/features/feature_factory.h"
#include "slam/features/feature_options.h"
#include "slam/registration/transform_estimation.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/sensor/route.h"
#include "slam/synthetic/session_simulator.h"

namespace duskmap {
namespace {

constexpr int kFrames[] = {0, 4, 8, 12};

// The box apartment without motion blur, on which the bounds were measured.
GeneratorConfig SmallConfig() {
  GeneratorConfig config;
  ApplyGeneratorModel("boxes-2026-12-02", &config);
  config.camera.exposure.motion_blur_scale = 0.0;
  config.lighting.light_texel_m = 0.1;          // coarser light map: faster preparation
  return config;
}

// Frames kFrames of the route of default session `route_index`, rendered in
// the light of default session `light_index` (as the generator seeds them).
std::vector<RgbdFrame> RenderFrames(const GeneratorConfig& config, const Scene& scene,
                                    size_t route_index, size_t light_index) {
  const uint64_t route_seed = DeriveSeed(config.seed, 100 + route_index);
  const std::vector<TimedPose> route =
      GenerateRoute(config.route, ApartmentPatrolRoute(), DeriveSeed(route_seed, 10));
  const SessionSpec& light = config.sessions[light_index];
  SessionSimulator simulator(config, scene, ParseClockTime(light.clock_time, light.name),
                             DeriveSeed(DeriveSeed(config.seed, 100 + light_index), 12));
  simulator.Settle(route.front().world_from_camera, 12);
  std::vector<RgbdFrame> frames;
  int next = 0;
  for (int k = 0; k <= kFrames[std::size(kFrames) - 1]; ++k) {
    RgbdFrame frame = simulator.Capture(route[k].world_from_camera);  // the camera runs every frame
    if (k == kFrames[next]) {
      frames.push_back(std::move(frame));
      ++next;
    }
  }
  return frames;
}

struct PairOutcome {
  RegistrationResult result;
  double error_m = 0.0;
  double error_deg = 0.0;
};

class TransformEstimationSynthetic : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    cv::setNumThreads(1);
    const GeneratorConfig config = SmallConfig();
    ApartmentOptions scene_options = config.scene;
    scene_options.seed = DeriveSeed(config.seed, 1);
    const Scene scene = BuildApartment(scene_options);
    map_ = new std::vector<RgbdFrame>(RenderFrames(config, scene, 0, 0));    // session 1, 16:46
    same_light_ = new std::vector<RgbdFrame>(RenderFrames(config, scene, 6, 0));  // route A, 16:46
    night_ = new std::vector<RgbdFrame>(RenderFrames(config, scene, 6, 5));  // route A, 19:35
  }
  static void TearDownTestSuite() {
    delete map_;
    delete same_light_;
    delete night_;
  }

  static std::vector<PairOutcome> Register(const std::vector<RgbdFrame>& queries) {
    FeatureOptions feature_options;  // default type (SURF), 1000 features
    const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(feature_options);
    std::vector<PairOutcome> outcomes;
    for (size_t i = 0; i < queries.size(); ++i) {
      const RgbdFrame& node = (*map_)[i];
      const RgbdFrame& query = queries[i];
      const FrameFeatures node_features = extractor->Extract(node.bgr, node.depth_m, &node.camera);
      const FrameFeatures query_features = extractor->Extract(query.bgr);
      PairOutcome outcome;
      outcome.result = EstimateTransform(RegistrationOptions(), node_features, node.camera,
                                         query_features, query.camera);
      const Rigid3d truth = node.world_from_camera->Inverse() * *query.world_from_camera;
      outcome.error_m = (outcome.result.node_from_query.translation - truth.translation).norm();
      outcome.error_deg =
          RotationAngleRad(outcome.result.node_from_query.rotation, truth.rotation) * 180.0 / M_PI;
      outcomes.push_back(outcome);
    }
    return outcomes;
  }

  static std::vector<RgbdFrame>* map_;
  static std::vector<RgbdFrame>* same_light_;
  static std::vector<RgbdFrame>* night_;
};

std::vector<RgbdFrame>* TransformEstimationSynthetic::map_ = nullptr;
std::vector<RgbdFrame>* TransformEstimationSynthetic::same_light_ = nullptr;
std::vector<RgbdFrame>* TransformEstimationSynthetic::night_ = nullptr;

std::string Describe(const PairOutcome& o) {
  return std::string(RegistrationStatusName(o.result.status)) + ", " +
         std::to_string(o.result.num_inliers) + " inliers (first pass " +
         std::to_string(o.result.inliers_first_pass) + " of " +
         std::to_string(o.result.matches_first_pass) + " matches), error " +
         std::to_string(o.error_m) + " m / " + std::to_string(o.error_deg) + " deg";
}

TEST_F(TransformEstimationSynthetic, SameLightPairsAreAcceptedWithTheTrueTransform) {
  const std::vector<PairOutcome> outcomes = Register(*same_light_);
  for (size_t i = 0; i < outcomes.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(kFrames[i]) + ": " + Describe(outcomes[i]));
    std::cout << "[ measured ] same-light frame " << kFrames[i] << ": " << Describe(outcomes[i]) << "\n";
    const PairOutcome& o = outcomes[i];
    EXPECT_TRUE(o.result.accepted());
    EXPECT_GE(o.result.num_inliers, 20);
    // Measured: 3.7-57 mm, 0.09-0.96 deg (frame 12 sees mostly far surfaces,
    // where the depth noise grows quadratically).
    EXPECT_LT(o.error_m, 0.08);
    EXPECT_LT(o.error_deg, 1.5);
  }
}

// Measured (docs/registration.md): 2 of the 4 night pairs are accepted
// (3.5 and 4.5 cm, 0.9 deg from the truth); frames 4 and 12 are rejected
// (7 matches; 7 inliers of 20). The night halves what registers; what is
// accepted is still right.
TEST_F(TransformEstimationSynthetic, DayNightPairsRegisterLessOftenButNeverWrongly) {
  const std::vector<PairOutcome> outcomes = Register(*night_);
  int accepted = 0;
  for (size_t i = 0; i < outcomes.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(kFrames[i]) + ": " + Describe(outcomes[i]));
    std::cout << "[ measured ] night frame " << kFrames[i] << ": " << Describe(outcomes[i]) << "\n";
    const PairOutcome& o = outcomes[i];
    EXPECT_TRUE(o.result.node_from_query.IsFinite());
    if (o.result.accepted()) {
      ++accepted;
      EXPECT_LT(o.error_m, 0.10);
      EXPECT_LT(o.error_deg, 2.0);
    } else {
      EXPECT_EQ(o.result.node_from_query.translation.norm(), 0.0);  // no pose carried
      EXPECT_LT(o.result.num_inliers, 20);
    }
  }
  EXPECT_GE(accepted, 1);
  EXPECT_LE(accepted, 3);  // the same pairs are all accepted in daylight
}

}  // namespace
}  // namespace duskmap
