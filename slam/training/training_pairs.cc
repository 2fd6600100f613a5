#include "slam/training/training_pairs.h"

#include <algorithm>
#include <memory>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/core/timer.h"
#include "slam/features/feature_factory.h"
#include "slam/features/patch_sampler.h"
#include "slam/synthetic/generator.h"
#include "slam/training/correspondence.h"

namespace duskmap {
namespace {

// One captured frame: its exact geometry, SIFT's keypoints and its patches' sampler.
struct CapturedFrame {
  ViewGeometry view;
  std::vector<cv::KeyPoint> keypoints;
  std::unique_ptr<PatchSampler> sampler;
};

std::unique_ptr<FeatureExtractor> SiftExtractor() {
  FeatureOptions features;
  features.type = "sift";
  features.max_features = 1000;
  return CreateFeatureExtractor(features);
}

// Session `time` of the scene, capturing `route`'s poses in order (the camera
// settled on the first, as the generator records a session).
std::vector<CapturedFrame> CaptureSession(const TrainingScene& scene, const Scene& apartment, size_t time,
                                          const std::vector<Rigid3d>& route, const FeatureExtractor& sift,
                                          const PatchSamplerOptions& patch) {
  const std::unique_ptr<SessionSimulator> simulator =
      StartSessionSimulator(scene.config, apartment, time, route.front());
  std::vector<CapturedFrame> frames(route.size());
  for (size_t k = 0; k < route.size(); ++k) {
    const RgbdFrame frame = simulator->Capture(route[k]);
    cv::Mat gray;
    cv::cvtColor(frame.bgr, gray, cv::COLOR_BGR2GRAY);
    CapturedFrame& out = frames[k];
    out.view.depth_m = simulator->last_view().depth_m.clone();  // exact, not the depth sensor's
    out.view.camera = frame.camera;
    out.view.world_from_camera = route[k];
    out.keypoints = sift.Extract(gray).keypoints;
    out.sampler = std::make_unique<PatchSampler>(gray, patch);
  }
  return frames;
}

// Keeps a seeded random subset of at most `limit` matches, in index_a order.
void KeepAtMost(int limit, uint64_t seed, std::vector<KeypointMatch>* matches) {
  if (static_cast<int>(matches->size()) <= limit) return;
  Rng rng(seed);
  for (int i = 0; i < limit; ++i) {
    const size_t j = i + static_cast<size_t>(rng() % (matches->size() - i));
    std::swap((*matches)[i], (*matches)[j]);
  }
  matches->resize(limit);
  std::sort(matches->begin(), matches->end(),
            [](const KeypointMatch& x, const KeypointMatch& y) { return x.index_a < y.index_a; });
}

void AppendPairs(const CapturedFrame& a, const CapturedFrame& b, const std::vector<KeypointMatch>& matches,
                 ScenePairs* out) {
  std::vector<cv::KeyPoint> keypoints_a, keypoints_b;
  for (const KeypointMatch& m : matches) {
    keypoints_a.push_back(a.keypoints[m.index_a]);
    keypoints_b.push_back(b.keypoints[m.index_b]);
  }
  const cv::Mat patches_a = a.sampler->Sample(keypoints_a);
  const cv::Mat patches_b = b.sampler->Sample(keypoints_b);
  const size_t patch_bytes = static_cast<size_t>(patches_a.cols);
  for (size_t i = 0; i < matches.size(); ++i) {
    const uint8_t* row_a = patches_a.ptr<uint8_t>(static_cast<int>(i));
    const uint8_t* row_b = patches_b.ptr<uint8_t>(static_cast<int>(i));
    out->patches.insert(out->patches.end(), row_a, row_a + patch_bytes);
    out->patches.insert(out->patches.end(), row_b, row_b + patch_bytes);
    for (int c = 0; c < 3; ++c) out->points_in_world.push_back(matches[i].point_in_world[c]);
  }
  out->pairs += static_cast<int64_t>(matches.size());
}

}  // namespace

std::vector<ImagePair> SelectImagePairs(int times, int frames, double same_time_share, uint64_t seed) {
  Rng rng(seed);
  std::vector<ImagePair> pairs;
  for (int a = 0; a < times; ++a) {
    for (int b = 0; b < times; ++b) {
      if (a == b) continue;
      for (int i = 0; i < frames; ++i) {
        const int d = a < b ? static_cast<int>(rng() % 3) : 1 + static_cast<int>(rng() % 2);
        if (i + d < frames) pairs.push_back({a, i, b, i + d});
      }
    }
  }
  for (int a = 0; a < times; ++a) {
    for (int i = 0; i < frames; ++i) {
      const bool chosen = static_cast<double>(rng() >> 11) * 0x1.0p-53 < same_time_share;
      const int d = 1 + static_cast<int>(rng() % 2);
      if (chosen && i + d < frames) pairs.push_back({a, i, a, i + d});
    }
  }
  return pairs;
}

ScenePairs RenderScenePairs(const TrainingScene& scene, const TrainingDataOptions& options) {
  options.Check();
  Stopwatch watch;
  const Scene apartment = BuildGeneratorScene(scene.config);
  std::vector<Rigid3d> route;
  for (const TimedPose& pose : GeneratorSessionRoute(scene.config, 0)) route.push_back(pose.world_from_camera);
  if (static_cast<int>(route.size()) > options.scenes.frames_per_hour) route.resize(options.scenes.frames_per_hour);
  SLAM_CHECK_MSG(!route.empty(), "a training scene's route has no frame");
  const std::unique_ptr<FeatureExtractor> sift = SiftExtractor();
  std::vector<std::vector<CapturedFrame>> sessions;
  for (size_t t = 0; t < scene.config.sessions.size(); ++t) {
    sessions.push_back(CaptureSession(scene, apartment, t, route, *sift, options.patch));
  }
  ScenePairs out;
  out.scene_index = scene.index;
  out.frames = static_cast<int>(sessions.size() * route.size());
  const uint64_t seed = DeriveSeed(scene.config.seed, 7001);
  const std::vector<ImagePair> image_pairs = SelectImagePairs(
      static_cast<int>(sessions.size()), static_cast<int>(route.size()), options.same_time_share, DeriveSeed(seed, 0));
  const CorrespondenceOptions correspondence = options.Correspondence();
  for (size_t k = 0; k < image_pairs.size(); ++k) {
    const ImagePair& p = image_pairs[k];
    const CapturedFrame& a = sessions[p.time_a][p.frame_a];
    const CapturedFrame& b = sessions[p.time_b][p.frame_b];
    std::vector<KeypointMatch> matches = MatchKeypoints(a.keypoints, a.view, b.keypoints, b.view, correspondence);
    KeepAtMost(options.max_pairs_per_image_pair, DeriveSeed(seed, 1 + k), &matches);
    AppendPairs(a, b, matches, &out);
  }
  out.image_pairs = static_cast<int>(image_pairs.size());
  out.wall_s = watch.ElapsedMs() / 1000.0;
  return out;
}

}  // namespace duskmap
