// The memory a map needs for localization, by component, counted from the
// data actually held (element sizes times counts plus container overheads
// that scale with the data). The Bayes filter belongs to the retrieval state,
// not to the Map: its bytes are passed in by the caller that owns it.
#pragma once

#include <cstddef>

#include "slam/map/map.h"

namespace duskmap {

struct MapMemory {
  size_t descriptors_bytes = 0;        // node descriptors as kept (codes + row scales)
  size_t keypoints_points_bytes = 0;   // packed keypoint and half-float 3D point of every feature
  size_t words_index_bytes = 0;        // stored word descriptors, node word ids and counts (+ a live vocabulary, by its owner)
  size_t graph_bytes = 0;              // node poses, cameras and metadata; links
  size_t filter_bytes = 0;             // Bayes filter state (given by its owner)
  size_t num_nodes = 0;

  size_t total_bytes() const {
    return descriptors_bytes + keypoints_points_bytes + words_index_bytes + graph_bytes +
           filter_bytes;
  }
  double bytes_per_node() const {
    return num_nodes ? static_cast<double>(total_bytes()) / num_nodes : 0.0;
  }
};

// Counts the map's components; filter_bytes is copied from the argument.
MapMemory ComputeMapMemory(const Map& map, size_t filter_bytes = 0);

// Peak resident set size of this process (VmHWM of /proc/self/status), in
// bytes; 0 where the platform does not report it.
size_t PeakResidentBytes();

}  // namespace duskmap
