// The reference's validation of localizations by an odometry cache (spec
// §9.2, RGBD/MaxOdomCacheSize). The cache holds the camera poses of the last
// `size` frames in the session's odometry frame and the localization links
// accepted among them. A new localization link (map node -> current frame) is
// validated by optimising a small graph: the cached frames chained by
// odometry links, the cached and the new localization links, and the map nodes
// they reference held at their map poses (the oldest one fixed, the others
// tied to it by stiff prior links standing in for the reference's pose
// priors). The link is rejected when the largest normalised link error
// (spec 7.4, prior links excluded) exceeds max_error_ratio. An accepted link
// enters the cache; the correction is applied only when the cache already
// held another localization link (delayed localization: one re-localization
// alone is never trusted).
//
// Deviations from the reference (documented in docs/engine.md): no
// LocalizationSmoothing (the correction comes from the link itself, as in
// the paper-era rule) and no second try without proximity links.
#pragma once

#include <deque>
#include <optional>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"
#include "slam/graph/pose_graph.h"
#include "slam/graph/pose_graph_optimizer.h"

namespace duskmap {

struct OdometryCacheOptions {
  int size = 10;                      // frames kept (RGBD/MaxOdomCacheSize), >= 2
  double max_error_ratio = 3.0;       // RGBD/OptimizeMaxError used by the validation, > 0
  double odometry_linear_sigma_m = 0.01;     // odometry link between consecutive frames
  double odometry_angular_sigma_rad = 0.01;
  double prior_sigma = 0.001;         // RGBD/LocalizationPriorError (m and rad)
  int max_iterations = 20;

  void Check() const;
};

enum class CacheValidation {
  kApplied,   // consistent with the cache, which already held a localization: apply it
  kWaiting,   // consistent (or alone), but the first localization in the cache: not applied
  kRejected,  // the optimised cache graph has a link error above max_error_ratio
};

const char* CacheValidationName(CacheValidation validation);

struct CacheValidationResult {
  CacheValidation status = CacheValidation::kRejected;
  double max_linear_ratio = 0.0;
  double max_angular_ratio = 0.0;
  int localization_links = 0;  // in the validated graph, the new one included
};

class OdometryCache {
 public:
  explicit OdometryCache(const OdometryCacheOptions& options);

  // Adds the current frame (call once per frame, before Validate); the
  // oldest frame and its localization links leave when the cache is full.
  void AddFrame(const Rigid3d& odom_from_camera);
  // Validates a localization of the current (last added) frame against map
  // node `node` at `map_from_node_camera`: node_camera_from_query is the
  // registration's transform and `information` its information. An accepted
  // (applied or waiting) link is kept in the cache.
  CacheValidationResult Validate(NodeId node, const Rigid3d& map_from_node_camera,
                                 const Rigid3d& node_camera_from_query,
                                 const Information6d& information);
  size_t num_frames() const { return frames_.size(); }
  size_t num_localization_links() const;

 private:
  struct CachedLink {
    NodeId node = 0;
    Rigid3d map_from_node_camera;
    Rigid3d node_camera_from_query;
    Information6d information = Information6d::Identity();
  };
  struct CachedFrame {
    Rigid3d odom_from_camera;
    std::vector<CachedLink> links;
  };

  // The graph a validation optimises: the referenced map nodes (ids 1.., in
  // node order, the first the fixed root, the others tied to it by priors),
  // then the cached frames in time order, with their odometry links and
  // localization links, `added` included on the last frame.
  struct CheckGraph {
    PoseGraph graph;
    LinkKey added;                 // the link being validated
    std::vector<LinkKey> priors;   // removed before the error check
  };
  CheckGraph BuildCheckGraph(const CachedLink& added) const;
  // Optimises `check` and measures its largest error ratios without the
  // priors into `result`; false when the solver fails or a ratio is too large.
  bool OptimizesWithinErrors(CheckGraph* check, CacheValidationResult* result) const;

  OdometryCacheOptions options_;
  std::deque<CachedFrame> frames_;
};

}  // namespace duskmap
