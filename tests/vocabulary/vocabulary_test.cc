#include "slam/vocabulary/vocabulary.h"

#include <numeric>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/vocabulary/synthetic_descriptors.h"

namespace duskmap {
namespace {

SyntheticDescriptors Generator(DescriptorKind kind) {
  SyntheticDescriptorOptions o;
  o.kind = kind;
  o.cols = kind == DescriptorKind::kFloat ? 128 : 32;
  return SyntheticDescriptors(o);
}

std::vector<int64_t> Range(int64_t first, int count) {
  std::vector<int64_t> ids(count);
  std::iota(ids.begin(), ids.end(), first);
  return ids;
}

// Frame k of a route sees landmarks [100 k, 100 k + 400): consecutive frames
// share 300 landmarks.
cv::Mat RouteFrame(const SyntheticDescriptors& gen, int k, uint64_t seed) {
  return gen.Observe(Range(100 * k, 400), 0, 1.0, seed);
}

TEST(Vocabulary, ReobservationsReuseWordsAndNewStructureCreatesWords) {
  for (DescriptorKind kind : {DescriptorKind::kFloat, DescriptorKind::kBinary}) {
    const SyntheticDescriptors gen = Generator(kind);
    Vocabulary vocab{VocabularyOptions()};
    const NodeQuantization first = vocab.AddNode(1, RouteFrame(gen, 0, 1), kind);
    EXPECT_EQ(first.new_words, 400);
    EXPECT_EQ(first.matched_words, 0);
    const NodeQuantization second = vocab.AddNode(2, RouteFrame(gen, 1, 2), kind);
    // 300 landmarks seen again (approximate search: a few are missed), 100 new.
    EXPECT_GE(second.matched_words, 270);
    EXPECT_LE(second.new_words, 130);
    EXPECT_EQ(vocab.num_words(), static_cast<size_t>(first.new_words + second.new_words));
    EXPECT_EQ(vocab.num_nodes(), 2u);
  }
}

TEST(Vocabulary, DeterministicForTheSameInput) {
  const SyntheticDescriptors gen = Generator(DescriptorKind::kFloat);
  Vocabulary a{VocabularyOptions()}, b{VocabularyOptions()};
  for (int k = 0; k < 8; ++k) {
    const cv::Mat frame = RouteFrame(gen, k % 5, 10 + k);
    EXPECT_EQ(a.AddNode(k + 1, frame, DescriptorKind::kFloat).words,
              b.AddNode(k + 1, frame, DescriptorKind::kFloat).words);
  }
  EXPECT_EQ(a.num_words(), b.num_words());
}

// The incrementally maintained KD-trees (rebuilt on doubling, exhaustive
// checks) quantize exactly as a brute-force index over the same words.
TEST(Vocabulary, IncrementalIndexQuantizesLikeABatchIndex) {
  const SyntheticDescriptors gen = Generator(DescriptorKind::kFloat);
  VocabularyOptions incremental_options;
  incremental_options.index.checks = 1000000;
  VocabularyOptions batch_options;
  batch_options.index.float_kind = IndexKind::kLinear;
  Vocabulary incremental(incremental_options), batch(batch_options);
  for (int k = 0; k < 12; ++k) {
    const cv::Mat frame = RouteFrame(gen, k % 7, 100 + k);
    EXPECT_EQ(incremental.AddNode(k + 1, frame, DescriptorKind::kFloat).words,
              batch.AddNode(k + 1, frame, DescriptorKind::kFloat).words)
        << "frame " << k;
  }
  EXPECT_GT(incremental.index_rebuilds(), 3);
  const cv::Mat probe = RouteFrame(gen, 3, 999);
  incremental.RebuildIndex();
  EXPECT_EQ(incremental.Quantize(probe, DescriptorKind::kFloat).words,
            batch.Quantize(probe, DescriptorKind::kFloat).words);
}

TEST(Vocabulary, QuantizeOnlyMatchesAddNodeAndChangesNothing) {
  for (DescriptorKind kind : {DescriptorKind::kFloat, DescriptorKind::kBinary}) {
    const SyntheticDescriptors gen = Generator(kind);
    Vocabulary vocab{VocabularyOptions()};
    for (int k = 0; k < 4; ++k) vocab.AddNode(k + 1, RouteFrame(gen, k, k), kind);
    const size_t words_before = vocab.num_words();
    const size_t bytes_before = vocab.MemoryBytes();
    const cv::Mat frame = RouteFrame(gen, 3, 77);  // 100 landmarks never seen
    const NodeQuantization lookup = vocab.Quantize(frame, kind);
    EXPECT_EQ(vocab.num_words(), words_before);
    EXPECT_EQ(vocab.MemoryBytes(), bytes_before);
    EXPECT_EQ(vocab.num_nodes(), 4u);
    const NodeQuantization added = vocab.AddNode(99, frame, kind);
    ASSERT_EQ(lookup.words.size(), added.words.size());
    for (size_t i = 0; i < added.words.size(); ++i) {
      if (added.words[i] <= static_cast<WordId>(words_before)) {
        EXPECT_EQ(lookup.words[i], added.words[i]);
      } else {
        EXPECT_EQ(lookup.words[i], kNoWord);
      }
    }
    EXPECT_EQ(lookup.new_words, added.new_words);
    EXPECT_EQ(lookup.matched_words, added.matched_words);
    // Add-then-remove restores the vocabulary's contents.
    const NodeRemoval removal = vocab.RemoveNode(99);
    EXPECT_EQ(static_cast<int>(removal.removed_words.size()), added.new_words);
    EXPECT_EQ(vocab.num_words(), words_before);
  }
}

TEST(Vocabulary, RemovingNodesRemovesExactlyTheirOrphanedWords) {
  const SyntheticDescriptors gen = Generator(DescriptorKind::kBinary);
  Vocabulary vocab{VocabularyOptions()};
  std::vector<NodeQuantization> q;
  for (int k = 0; k < 6; ++k) q.push_back(vocab.AddNode(k + 1, RouteFrame(gen, k, k), DescriptorKind::kBinary));
  // Words only node 6 references.
  std::vector<WordId> expected;
  for (WordId w : vocab.inverted_index().NodeWords(6)) {
    if (vocab.inverted_index().References(w).size() == 1) expected.push_back(w);
  }
  ASSERT_FALSE(expected.empty());
  const size_t before = vocab.num_words();
  const NodeRemoval r = vocab.RemoveNode(6);
  EXPECT_TRUE(r.was_present);
  EXPECT_EQ(r.removed_words, expected);
  EXPECT_EQ(vocab.num_words(), before - expected.size());
  for (WordId w : expected) EXPECT_FALSE(vocab.ContainsWord(w));
  // Removed twice: a defined no-op.
  const NodeRemoval again = vocab.RemoveNode(6);
  EXPECT_FALSE(again.was_present);
  EXPECT_TRUE(again.removed_words.empty());
  EXPECT_EQ(vocab.num_words(), before - expected.size());
  // Index consistency: every word a remaining node references exists and
  // lists the node; every removed word is gone from the inverted index.
  for (NodeId n : vocab.inverted_index().Nodes()) {
    for (WordId w : vocab.inverted_index().NodeWords(n)) {
      EXPECT_TRUE(vocab.ContainsWord(w));
      const auto& refs = vocab.inverted_index().References(w);
      EXPECT_TRUE(std::any_of(refs.begin(), refs.end(), [n](const WordReference& x) { return x.node == n; }));
    }
  }
  for (WordId w : expected) EXPECT_TRUE(vocab.inverted_index().References(w).empty());
  // The frame of node 6 now creates new words for what was removed.
  const NodeQuantization re = vocab.Quantize(RouteFrame(gen, 5, 5), DescriptorKind::kBinary);
  for (WordId w : re.words) EXPECT_TRUE(w == kNoWord || vocab.ContainsWord(w));
  // Remove everything: the vocabulary is empty and usable again.
  for (NodeId n = 1; n <= 5; ++n) vocab.RemoveNode(n);
  EXPECT_EQ(vocab.num_words(), 0u);
  EXPECT_EQ(vocab.AddNode(7, RouteFrame(gen, 0, 1), DescriptorKind::kBinary).new_words, 400);
}

TEST(Vocabulary, EmptyVocabularyBadFramesAndLimits) {
  const SyntheticDescriptors gen = Generator(DescriptorKind::kFloat);
  Vocabulary vocab{VocabularyOptions()};
  const NodeQuantization empty_lookup = vocab.Quantize(RouteFrame(gen, 0, 1), DescriptorKind::kFloat);
  EXPECT_EQ(empty_lookup.matched_words, 0);
  EXPECT_EQ(empty_lookup.new_words, 400);
  for (WordId w : empty_lookup.words) EXPECT_EQ(w, kNoWord);
  // No features / fewer than Kp/BadSignRatio x Kp/MaxFeatures = 200.
  const NodeQuantization none = vocab.AddNode(1, cv::Mat(), DescriptorKind::kFloat);
  EXPECT_TRUE(none.bad_signature);
  const NodeQuantization few = vocab.AddNode(2, gen.Random(150, 3), DescriptorKind::kFloat);
  EXPECT_TRUE(few.bad_signature);
  EXPECT_EQ(vocab.num_words(), 0u);
  EXPECT_EQ(vocab.num_nodes(), 2u);
  // Only the first Kp/MaxFeatures rows are quantized; n_j counts all rows.
  const NodeQuantization many = vocab.AddNode(3, gen.Random(1000, 4), DescriptorKind::kFloat);
  EXPECT_EQ(many.words.size(), 400u);
  EXPECT_EQ(many.num_features, 1000);
  EXPECT_EQ(vocab.inverted_index().NodeFeatureCount(3), 1000);
  EXPECT_THROW(vocab.AddNode(3, gen.Random(300, 5), DescriptorKind::kFloat), InputError);
  EXPECT_THROW(vocab.AddNode(4, cv::Mat::zeros(300, 32, CV_8U), DescriptorKind::kBinary), InputError);
  EXPECT_THROW(vocab.AddNode(5, cv::Mat::zeros(300, 64, CV_32F), DescriptorKind::kFloat), InputError);
}

TEST(VocabularyOptions, Check) {
  VocabularyOptions o;
  o.nndr_ratio = 1.5;
  EXPECT_THROW(o.Check(), ConfigError);
  o = VocabularyOptions();
  o.max_features_per_node = -1;
  EXPECT_THROW(Vocabulary{o}, ConfigError);
  EXPECT_EQ(VocabularyOptions().MinFeatures(), 200);
}

}  // namespace
}  // namespace duskmap
