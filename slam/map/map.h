// The multi-session map: sessions, nodes (poses, features, word ids), links
// with information matrices, the vocabulary's words, and the metadata that
// says how it was built (feature type and every parameter). Only the engine's
// mapping phase mutates a Map; localization works on a const Map. The store
// (map_store.h) saves and loads it.
#pragma once

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"
#include "slam/features/frame_features.h"
#include "slam/map/compact_features.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

// How the map's features were made. A map is only usable with the same
// extractor, so loading checks feature_type against the caller's.
struct MapMetadata {
  std::string feature_type;              // FeatureOptions::type, e.g. "surf"
  std::string feature_parameters_json;   // every extractor parameter, as JSON text
  std::string engine_parameters_json;    // the engine options that built the map, as JSON text
  DescriptorKind descriptor_kind = DescriptorKind::kFloat;
  int descriptor_cv_type = -1;  // OpenCV type of a descriptor row (CV_32F, CV_8U); -1 = no node yet
  int descriptor_cols = 0;      // elements per descriptor row
  // How the nodes keep float descriptors (compact_features.h); every node of
  // a map uses this storage.
  DescriptorStorage descriptor_storage = DescriptorStorage::kFloat32;
  // How the vocabulary keeps float words (vocabulary/word_types.h,
  // WordRowFormat); the words a map stores are in this form. Binary words
  // are exact whatever this says.
  DescriptorStorage word_storage = DescriptorStorage::kFloat32;
};

struct MapSession {
  SessionId id = 0;
  std::string name;                       // the input session's name, e.g. "1", "A"
  std::optional<std::string> clock_time;  // local "HH:MM" when known
};

struct MapNode {
  NodeId id = 0;
  SessionId session = 0;
  int64_t frame_index = 0;   // position of the frame in its input session
  double timestamp_s = 0.0;  // the frame's timestamp, seconds
  Rigid3d map_from_body;     // optimised pose in the map frame
  Rigid3d odom_from_body;    // odometry pose in its session's odometry frame
  Rigid3d body_from_camera;  // camera extrinsics of the frame
  PinholeCamera camera;      // intrinsics of the frame
  std::optional<Rigid3d> truth_from_camera;  // ground truth when the dataset had it
  // Keypoints, descriptors, 3D points (camera frame), kept compact;
  // features.Decode() gives the FrameFeatures that registration uses.
  CompactFeatures features;
  // The node's words as the vocabulary held them when mapping finished:
  // distinct ids (increasing), each word's occurrences in the node, and n_j,
  // the node's feature count for tf-idf. With the map's words they restore the
  // vocabulary exactly (map_vocabulary.h).
  std::vector<WordId> word_ids;
  std::vector<int32_t> word_counts;  // parallel to word_ids, >= 1
  int32_t vocabulary_features = 0;   // n_j

  Rigid3d map_from_camera() const { return map_from_body * body_from_camera; }
};

// The vocabulary's words as stored: one row per word, in the form
// MapMetadata::word_storage says (VocabularySnapshot::descriptors).
struct MapWords {
  std::vector<WordId> ids;  // increasing
  cv::Mat descriptors;      // one stored row per id
  WordId next_word_id = 1;  // the id a new word would get (ids are never reused)
  // The vocabulary's NN index as Vocabulary::Import builds it from these
  // words (VocabularySnapshot::index_state), stored with the map so that a
  // load restores it instead of building it; empty when not stored.
  std::vector<uint8_t> index_state;
  // Set by the map store when a stored index could not be read (checksum,
  // version): the reason the vocabulary rebuilds it. "" otherwise.
  std::string index_problem;
};

class Map {
 public:
  Map() = default;
  explicit Map(MapMetadata metadata) : metadata_(std::move(metadata)) {}

  const MapMetadata& metadata() const { return metadata_; }
  MapMetadata& mutable_metadata() { return metadata_; }

  // Appends a session with the next id (0, 1, ...) and returns that id.
  SessionId AddSession(const std::string& name, const std::optional<std::string>& clock_time);
  const std::vector<MapSession>& sessions() const { return sessions_; }

  // Adds a node. Its id must be larger than every id seen so far (ids are
  // never reused), its session must exist, and its descriptors must match
  // the map's (the first node fixes descriptor type and width; the storage
  // must be metadata().descriptor_storage). Throws InputError otherwise.
  void AddNode(MapNode node);
  // Removes a node and every link touching it (graph reduction).
  void RemoveNode(NodeId id);
  bool HasNode(NodeId id) const { return nodes_.count(id) > 0; }
  const MapNode& node(NodeId id) const;  // SLAM_CHECK that it exists
  MapNode& mutable_node(NodeId id);
  const std::map<NodeId, MapNode>& nodes() const { return nodes_; }
  NodeId last_node_id() const { return last_node_id_; }  // 0 when none was ever added
  NodeId NextNodeId() const { return last_node_id_ + 1; }
  // Raises the last id seen to `id` (the store restores it, so that ids of
  // removed nodes are never reused).
  void ReserveNodeIdsUpTo(NodeId id) { last_node_id_ = std::max(last_node_id_, id); }

  // Adds a link between existing distinct nodes; at most one link per pair of
  // nodes (in either direction). Throws InputError otherwise.
  void AddLink(const Link& link);
  // Removes the link between a and b (either direction); false when none.
  bool RemoveLink(NodeId a, NodeId b);
  bool HasLink(NodeId a, NodeId b) const;
  const std::map<std::pair<NodeId, NodeId>, Link>& links() const { return links_; }
  // Links touching `id`, in either direction, as stored.
  std::vector<Link> LinksOf(NodeId id) const;
  std::vector<NodeId> NodesOfSession(SessionId session) const;

  // Groups of sessions joined by links (odometry links never cross sessions,
  // so groups are formed by loop-closure, proximity and merged links), each
  // sorted, ordered by their smallest session id. Sessions without nodes
  // form their own group.
  std::vector<std::vector<SessionId>> ConnectedSessionGroups() const;

  const MapWords& words() const { return words_; }
  // Replaces the stored words (the engine snapshots its vocabulary here).
  void SetWords(MapWords words);
  // Stores the vocabulary index built from the current words (MapWords::
  // index_state); the words are unchanged.
  void SetWordIndexState(std::vector<uint8_t> state) {
    words_.index_state = std::move(state);
    words_.index_problem.clear();
  }

 private:
  void CheckDescriptors(const MapNode& node);

  MapMetadata metadata_;
  std::vector<MapSession> sessions_;
  std::map<NodeId, MapNode> nodes_;
  std::map<std::pair<NodeId, NodeId>, Link> links_;  // key (from, to)
  std::map<NodeId, std::set<NodeId>> adjacency_;     // both directions
  NodeId last_node_id_ = 0;
  MapWords words_;
};

}  // namespace duskmap
