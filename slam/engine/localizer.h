// The localization-only phase (spec §9) over a const Map: no node, link or
// word survives the frame that created it. The session starts with no prior
// pose: proximity detection searches around the corrected pose, which until
// the first re-localization is the odometry pose taken as a map pose (the
// reference with -loc_null; localization.proximity_before_relocalized), and is
// tried before the loop closure hypothesis (the reference computes the global
// transform after proximity). A proximity link must be no longer than
// proximity.path_filtering_radius_m, unless its target is the hypothesis,
// which is then linked as a loop closure (spec §5.4). As soon as one
// candidate's transform is accepted the others are
// not tested (paper era, spec §9.3), and the map->odometry correction is set
// from that link: map_from_odom = map_from_node_camera * node_from_query *
// odom_from_camera^-1. With localization.odometry_cache_size > 0 an accepted
// transform must also pass the reference's odometry-cache validation (spec
// §9.2, odometry_cache.h) and is applied only once the cache holds an earlier
// localization; a transform the validation rejects lets the next candidate be
// tried.
//
// The loop-closure state starts from the vocabulary the map stores (words,
// node word counts, n_j: the mapper's at the end of mapping, restored
// exactly), the map's links as the place graph, and every node as a
// candidate place; an in-memory map and the same map saved and loaded give
// identical results.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "slam/core/rgbd_frame.h"
#include "slam/engine/engine_options.h"
#include "slam/engine/localization_record.h"
#include "slam/engine/odometry_cache.h"
#include "slam/features/feature_extractor.h"
#include "slam/map/map.h"
#include "slam/retrieval/loop_closure_detector.h"

namespace duskmap {

class Localizer {
 public:
  // Throws ConfigError when the map was built with another feature type.
  // `words`: the vocabulary's words when the map was loaded without them
  // (MapLoadOptions::load_words false); nullptr = map.words(). They are
  // imported in the constructor and not referenced afterwards.
  Localizer(const Map& map, const EngineOptions& options, const MapWords* words = nullptr);
  ~Localizer();

  LocalizationRecord ProcessFrame(const RgbdFrame& frame);
  LocalizationRecord ProcessFrame(const RgbdFrame& frame, const FrameFeatures& features);

  const std::optional<Rigid3d>& map_from_odom() const { return map_from_odom_; }
  const LoopClosureDetector& loop_closure() const { return *lcd_; }

 private:
  struct Candidate {
    NodeId node = 0;
    LinkType type = LinkType::kLoopClosure;
    std::optional<double> search_distance_m;  // proximity: distance to the pose estimate
    // A proximity target that is also the accepted LCD hypothesis: linked as a
    // loop closure, without proximity's length limit (spec §5.4).
    bool is_hypothesis = false;
  };
  std::vector<Candidate> ProximityCandidates(const Rigid3d& odom_from_camera,
                                             LocalizationRecord* record);
  enum class Attempt { kRejected, kApplied, kWaiting };
  Attempt TryCandidate(const Candidate& candidate, const RgbdFrame& frame,
                       const FrameFeatures& features, LocalizationRecord* record);
  void UpdateDistance(const RgbdFrame& frame, LocalizationRecord* record);

  const Map& map_;
  EngineOptions options_;
  RegistrationOptions registration_;
  std::unique_ptr<FeatureMatcher> matcher_;  // nullptr: registration's NNDR
  std::unique_ptr<FeatureExtractor> extractor_;  // made by the first ProcessFrame(frame)
  std::unique_ptr<LoopClosureDetector> lcd_;
  std::optional<Rigid3d> map_from_odom_;
  std::unique_ptr<OdometryCache> cache_;  // only with localization.odometry_cache_size > 0
  SessionId localized_session_ = -1;  // session of the last matched node
  std::optional<Eigen::Vector3d> last_odom_position_;
  double distance_since_last_m_ = 0.0;
};

}  // namespace duskmap
