#include "slam/vocabulary/inverted_index.h"

#include <algorithm>
#include <map>
#include <random>
#include <vector>

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

TEST(InvertedIndex, ReferencesKeepTheirOrderThroughGrowthAndRemoval) {
  InvertedIndex index;
  for (NodeId n = 1; n <= 6; ++n) index.AddNode(n, {9, static_cast<WordId>(100 + n)}, 4);
  auto nodes_of = [&index](WordId w) {
    std::vector<NodeId> nodes;
    for (const WordReference& r : index.References(w)) nodes.push_back(r.node);
    return nodes;
  };
  EXPECT_EQ(nodes_of(9), (std::vector<NodeId>{1, 2, 3, 4, 5, 6}));
  index.RemoveNode(3);
  index.RemoveNode(1);
  EXPECT_EQ(nodes_of(9), (std::vector<NodeId>{2, 4, 5, 6}));
  for (NodeId n : {2, 5, 6}) index.RemoveNode(n);
  EXPECT_EQ(nodes_of(9), (std::vector<NodeId>{4}));  // back to the inline reference
  EXPECT_EQ(index.References(9)[0].count, 1);
  EXPECT_EQ(nodes_of(104), (std::vector<NodeId>{4}));
  EXPECT_TRUE(index.References(101).empty());
  EXPECT_EQ(index.num_words(), 2u);
}

// The packed word lists (a removed word's position goes to the last list)
// against a plain model, under random additions and removals.
TEST(InvertedIndex, MatchesAPlainModelUnderRandomAddsAndRemovals) {
  std::mt19937 rng(7);
  InvertedIndex index;
  std::map<NodeId, std::vector<WordId>> model;  // node -> its words (with repeats)
  NodeId next_node = 1;
  for (int step = 0; step < 600; ++step) {
    if (model.empty() || rng() % 3 != 0) {
      std::vector<WordId> words(1 + rng() % 12);
      for (WordId& w : words) w = 1 + static_cast<WordId>(rng() % 80);
      index.AddNode(next_node, words, static_cast<int>(words.size()) + 3);
      model[next_node++] = words;
    } else {
      auto it = model.begin();
      std::advance(it, rng() % model.size());
      ASSERT_TRUE(index.RemoveNode(it->first).has_value());
      model.erase(it);
    }
    if (step % 50 != 49) continue;
    index.ShrinkToFit();
    std::map<WordId, std::vector<std::pair<NodeId, int>>> expected;
    for (const auto& [node, words] : model) {
      std::map<WordId, int> counts;
      for (WordId w : words) ++counts[w];
      for (const auto& [w, c] : counts) expected[w].push_back({node, c});
    }
    ASSERT_EQ(index.num_words(), expected.size());
    for (WordId w = 1; w <= 80; ++w) {
      std::vector<std::pair<NodeId, int>> got;
      for (const WordReference& r : index.References(w)) got.push_back({r.node, r.count});
      // Nodes are added in increasing order and removal keeps the order.
      EXPECT_EQ(got, expected[w]) << "word " << w << " at step " << step;
    }
  }
}

}  // namespace
}  // namespace duskmap
