#include "slam/vocabulary/inverted_index.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(InvertedIndex, CountsOccurrencesAndReportsOrphans) {
  InvertedIndex index;
  index.AddNode(1, {5, 5, 6, kNoWord, 7}, 10);
  index.AddNode(2, {6, 8}, 2);
  ASSERT_EQ(index.References(5).size(), 1u);
  EXPECT_EQ(index.References(5)[0].count, 2);
  EXPECT_FLOAT_EQ(index.References(5)[0].inverse_node_features, 0.1f);
  EXPECT_EQ(index.References(6).size(), 2u);
  EXPECT_EQ(index.NodeWords(1), (std::vector<WordId>{5, 6, 7}));
  EXPECT_EQ(index.NodeFeatureCount(1), 10);
  EXPECT_EQ(index.num_words(), 4u);
  const auto orphans = index.RemoveNode(1);
  ASSERT_TRUE(orphans.has_value());
  EXPECT_EQ(*orphans, (std::vector<WordId>{5, 7}));
  EXPECT_EQ(index.References(6).size(), 1u);
  EXPECT_FALSE(index.RemoveNode(1).has_value());
  EXPECT_THROW(index.AddNode(2, {}, 0), InputError);
  EXPECT_EQ(index.Nodes(), (std::vector<NodeId>{2}));
}

}  // namespace
}  // namespace duskmap
