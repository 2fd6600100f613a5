#include "slam/map/map_memory.h"

#include <fstream>
#include <set>
#include <string>

namespace duskmap {
namespace {

// A std::map node: three pointers and a colour word besides the value.
constexpr size_t kTreeNodeOverhead = 4 * sizeof(void*);

// The node record itself (poses, camera, ids) in the node map, plus its
// adjacency set entry.
size_t NodeGraphBytes() {
  return sizeof(MapNode) + sizeof(NodeId) + 2 * kTreeNodeOverhead + sizeof(std::set<NodeId>);
}

}  // namespace

MapMemory ComputeMapMemory(const Map& map, size_t filter_bytes) {
  MapMemory memory;
  memory.num_nodes = map.nodes().size();
  for (const auto& [id, node] : map.nodes()) {
    memory.descriptors_bytes += node.features.DescriptorMemoryBytes();
    memory.keypoints_points_bytes += node.features.KeypointPointMemoryBytes();
    // The node's words and their counts (a live vocabulary's inverted index
    // is its owner's to add: Vocabulary::MemoryBytes).
    memory.words_index_bytes +=
        node.word_ids.size() * sizeof(WordId) + node.word_counts.size() * sizeof(int32_t);
    memory.graph_bytes += NodeGraphBytes();
  }
  const MapWords& words = map.words();
  memory.words_index_bytes += words.ids.size() * sizeof(WordId) +
                              words.descriptors.total() * words.descriptors.elemSize();
  memory.graph_bytes += map.links().size() *
                        (sizeof(Link) + kTreeNodeOverhead + 2 * sizeof(NodeId));
  memory.filter_bytes = filter_bytes;
  return memory;
}

size_t PeakResidentBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // kB
  }
  return 0;
}

}  // namespace duskmap
