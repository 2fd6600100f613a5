#include "slam/retrieval/likelihood.h"

#include <cmath>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

auto All() {
  return [](NodeId) { return true; };
}

TEST(Likelihood, TfIdfMatchesTheReferenceFormula) {
  InvertedIndex index;
  index.AddNode(1, {1, 2, 3, 4}, 4);
  index.AddNode(2, {1, 2, 5, 6}, 4);
  index.AddNode(3, {1, 7, 8, 9}, 4);
  index.AddNode(10, {1, 2, 3, 10}, 4);  // the query, already added (mapping)
  const Likelihood l = ComputeLikelihood(index, {1, 2, 3, 10}, true,
                                         [](NodeId n) { return n != 10; }, 3);
  // N = 4; word 1 in 4 nodes (idf 0, skipped), word 2 in 3, word 3 in 2.
  const double idf2 = std::log10(4.0 / 3.0), idf3 = std::log10(4.0 / 2.0);
  EXPECT_NEAR(l.Raw(1), (idf2 + idf3) / 4.0, 1e-6);
  EXPECT_NEAR(l.Raw(2), idf2 / 4.0, 1e-6);
  EXPECT_EQ(l.Raw(3), 0.0f);
  EXPECT_EQ(l.Raw(10), 0.0f);  // not a candidate
  // Lookup-only query (not in the index) counts as one more node: same scores.
  InvertedIndex without;
  without.AddNode(1, {1, 2, 3, 4}, 4);
  without.AddNode(2, {1, 2, 5, 6}, 4);
  without.AddNode(3, {1, 7, 8, 9}, 4);
  const Likelihood lookup = ComputeLikelihood(without, {1, 2, 3}, false, All(), 3);
  EXPECT_NEAR(lookup.Raw(1), l.Raw(1), 1e-6);
  EXPECT_NEAR(lookup.Raw(2), l.Raw(2), 1e-6);
}

TEST(Likelihood, RareWordsScoreHigherAndIdenticalFramesHighest) {
  InvertedIndex index;
  // Words 1-3 are common (in nodes 1-6), 100+ are rare.
  for (NodeId n = 1; n <= 6; ++n) index.AddNode(n, {1, 2, 3, static_cast<WordId>(100 + n)}, 4);
  index.AddNode(7, {1, 2, 3, 101, 102}, 5);  // shares the rare words of 1 and 2
  index.AddNode(8, {1, 2, 3, 101, 102}, 5);  // identical to the query
  const std::vector<WordId> query = {1, 2, 3, 101, 102};
  const Likelihood l = ComputeLikelihood(index, query, false, All(), 8);
  EXPECT_GT(l.Raw(1), l.Raw(3));  // one rare word beats only common words
  EXPECT_GT(l.Raw(7), l.Raw(1));  // two rare words beat one
  EXPECT_EQ(l.Raw(7), l.Raw(8));
  for (NodeId n = 1; n <= 6; ++n) EXPECT_LT(l.Raw(n), l.Raw(8));
  EXPECT_GE(l.Adjusted(8), l.Adjusted(1));
}

TEST(Likelihood, NormalisationAndVirtualPlace) {
  Likelihood l;
  l.computed = true;
  l.raw = {{1, 1.0f}, {2, 1.0f}, {3, 1.0f}, {4, 5.0f}};
  AdjustLikelihood(&l);
  // mean 2, population stddev sqrt(3).
  EXPECT_NEAR(l.mean, 2.0, 1e-6);
  EXPECT_NEAR(l.stddev, std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(l.Adjusted(4), (5.0 - (std::sqrt(3.0) - 1e-4)) / 2.0, 1e-5);
  EXPECT_EQ(l.Adjusted(1), 1.0f);
  EXPECT_EQ(l.Adjusted(99), 1.0f);  // a candidate sharing no word
  EXPECT_NEAR(l.virtual_place, 2.0 / std::sqrt(3.0) + 1.0, 1e-5);
  // All equal (sigma = 0): virtual place 2, nobody adjusted.
  Likelihood flat;
  flat.computed = true;
  flat.raw = {{1, 0.5f}, {2, 0.5f}};
  AdjustLikelihood(&flat);
  EXPECT_EQ(flat.virtual_place, 2.0f);
  EXPECT_TRUE(flat.adjusted.empty());
  // Empty index: nothing scored, virtual place 2.
  const Likelihood empty = ComputeLikelihood(InvertedIndex(), {1, 2}, false, All(), 0);
  EXPECT_TRUE(empty.raw.empty());
  EXPECT_EQ(empty.virtual_place, 2.0f);
  EXPECT_EQ(Likelihood().Adjusted(1), 0.0f);  // not computed
}

}  // namespace
}  // namespace duskmap
