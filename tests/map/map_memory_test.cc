#include "slam/map/map_memory.h"

#include <gtest/gtest.h>

#include "tests/map/test_map.h"

namespace duskmap {
namespace {

TEST(ComputeMapMemory, CountsComponents) {
  const Map map = testing::MakeTestMap(5, 40, /*binary=*/false);
  const MapMemory memory = ComputeMapMemory(map, /*filter_bytes=*/1234);
  EXPECT_EQ(memory.num_nodes, 10u);
  EXPECT_EQ(memory.descriptors_bytes, 10u * 40 * 64 * 4);
  // Packed keypoints (12 bytes) and half-float points (6 bytes).
  EXPECT_EQ(memory.keypoints_points_bytes, 10u * 40 * (12 + 6));
  // What the map holds of the vocabulary: 15 word ids and counts per node,
  // and 6 stored words (id + 64 floats).
  EXPECT_EQ(memory.words_index_bytes, 10u * 15 * (4 + 4) + 6 * (4 + 64 * 4));
  EXPECT_GT(memory.graph_bytes, 10u * sizeof(MapNode));
  EXPECT_EQ(memory.filter_bytes, 1234u);
  EXPECT_EQ(memory.total_bytes(), memory.descriptors_bytes + memory.keypoints_points_bytes +
                                      memory.words_index_bytes + memory.graph_bytes + 1234u);
  EXPECT_DOUBLE_EQ(memory.bytes_per_node(), memory.total_bytes() / 10.0);
}

TEST(ComputeMapMemory, BinaryDescriptorsAreSmaller) {
  const MapMemory binary = ComputeMapMemory(testing::MakeTestMap(5, 40, true));
  EXPECT_EQ(binary.descriptors_bytes, 10u * 40 * 32);
}

TEST(ComputeMapMemory, QuantizedDescriptorsTakeAQuarterPlusRowScales) {
  const MapMemory quantized =
      ComputeMapMemory(testing::MakeTestMap(5, 40, false, 7, DescriptorStorage::kUint8));
  EXPECT_EQ(quantized.descriptors_bytes, 10u * 40 * (64 + 2 * 4));
}

TEST(PeakResidentBytes, ReportsThisProcess) {
  EXPECT_GT(PeakResidentBytes(), 1u << 20);  // any process linking OpenCV exceeds 1 MiB
}

}  // namespace
}  // namespace duskmap
