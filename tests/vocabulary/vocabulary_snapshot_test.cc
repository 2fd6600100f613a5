#include "slam/vocabulary/vocabulary_snapshot.h"

#include <numeric>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/vocabulary/synthetic_descriptors.h"
#include "slam/vocabulary/vocabulary.h"

namespace duskmap {
namespace {

SyntheticDescriptors Generator(DescriptorKind kind) {
  SyntheticDescriptorOptions o;
  o.kind = kind;
  o.cols = kind == DescriptorKind::kFloat ? 128 : 32;
  return SyntheticDescriptors(o);
}

cv::Mat RouteFrame(const SyntheticDescriptors& gen, int k, uint64_t seed) {
  std::vector<int64_t> ids(400);
  std::iota(ids.begin(), ids.end(), 100 * k);
  return gen.Observe(ids, 0, 1.0, seed);
}

// A vocabulary with history: 10 nodes, one bad signature, two removed
// nodes (so word ids have gaps and next_word_id is past removed words).
void Fill(Vocabulary* vocab, const SyntheticDescriptors& gen, DescriptorKind kind) {
  for (int k = 0; k < 10; ++k) vocab->AddNode(k + 1, RouteFrame(gen, k % 7, k), kind);
  vocab->AddNode(11, gen.Random(50, 3), kind);  // bad signature: no words, n_j = 50
  vocab->RemoveNode(10);
  vocab->RemoveNode(4);
}

TEST(VocabularySnapshot, ExportImportRestoresWordsReferencesAndIds) {
  for (DescriptorKind kind : {DescriptorKind::kFloat, DescriptorKind::kBinary}) {
    SCOPED_TRACE(kind == DescriptorKind::kFloat ? "float" : "binary");
    const SyntheticDescriptors gen = Generator(kind);
    VocabularyOptions options;
    options.index.checks = 1000000;  // exhaustive search: lookups independent of tree shape
    Vocabulary original(options);
    Fill(&original, gen, kind);
    const VocabularySnapshot snapshot = original.Export();
    ASSERT_EQ(snapshot.word_ids.size(), original.num_words());
    EXPECT_EQ(snapshot.nodes.size(), 9u);
    EXPECT_GT(snapshot.next_word_id, snapshot.word_ids.back());

    Vocabulary restored(options);
    restored.Import(snapshot);
    EXPECT_TRUE(restored.Export() == snapshot);
    EXPECT_EQ(restored.num_words(), original.num_words());
    EXPECT_EQ(restored.num_nodes(), original.num_nodes());
    for (NodeId n : original.inverted_index().Nodes()) {
      EXPECT_EQ(restored.inverted_index().NodeWords(n), original.inverted_index().NodeWords(n));
      EXPECT_EQ(restored.inverted_index().NodeFeatureCount(n), original.inverted_index().NodeFeatureCount(n));
      for (WordId w : original.inverted_index().NodeWords(n)) {
        const auto& a = original.inverted_index().References(w);
        const auto& b = restored.inverted_index().References(w);
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
          EXPECT_EQ(a[i].node, b[i].node);
          EXPECT_EQ(a[i].count, b[i].count);
          EXPECT_EQ(a[i].inverse_node_features, b[i].inverse_node_features);
        }
      }
    }
    // Same lookups, and the same words created next (ids continue, not reused).
    const cv::Mat frame = RouteFrame(gen, 8, 99);
    EXPECT_EQ(restored.Quantize(frame, kind).words, original.Quantize(frame, kind).words);
    const NodeQuantization a = original.AddNode(20, frame, kind);
    const NodeQuantization b = restored.AddNode(20, frame, kind);
    EXPECT_EQ(a.words, b.words);
    EXPECT_GT(a.new_words, 0);
    EXPECT_TRUE(restored.Export() == original.Export());
    // Removing a node after the import removes exactly the same orphans.
    EXPECT_EQ(restored.RemoveNode(3).removed_words, original.RemoveNode(3).removed_words);
  }
}

// Quantized float words: the snapshot carries the stored rows (offset, step
// and codes), so an import restores the very same words, whatever the
// importing vocabulary's own word storage says; lookups and new words
// continue exactly as in the exporting vocabulary.
TEST(VocabularySnapshot, QuantizedWordsRoundTripExactly) {
  const SyntheticDescriptors gen = Generator(DescriptorKind::kFloat);
  VocabularyOptions options;
  options.index.checks = 1000000;
  options.index.float_storage = DescriptorStorage::kUint8;
  Vocabulary original(options);
  Fill(&original, gen, DescriptorKind::kFloat);
  const VocabularySnapshot snapshot = original.Export();
  EXPECT_EQ(snapshot.float_storage, DescriptorStorage::kUint8);
  EXPECT_EQ(snapshot.descriptors.type(), CV_8U);
  EXPECT_EQ(snapshot.DescriptorCols(), 128);
  EXPECT_EQ(snapshot.descriptors.cols, 128 + 8);
  VocabularyOptions float_options = options;
  float_options.index.float_storage = DescriptorStorage::kFloat32;
  Vocabulary restored(float_options);
  restored.Import(snapshot);
  EXPECT_TRUE(restored.Export() == snapshot);
  const cv::Mat frame = RouteFrame(gen, 5, 77);
  EXPECT_EQ(restored.Quantize(frame, DescriptorKind::kFloat).words,
            original.Quantize(frame, DescriptorKind::kFloat).words);
  EXPECT_EQ(restored.AddNode(30, frame, DescriptorKind::kFloat).words,
            original.AddNode(30, frame, DescriptorKind::kFloat).words);
  EXPECT_TRUE(restored.Export() == original.Export());
  // The same frames with float words: the same word count within a few
  // percent (quantization moves few nearest-neighbour decisions), in more bytes.
  Vocabulary exact(float_options);
  Fill(&exact, gen, DescriptorKind::kFloat);
  const double words_ratio = static_cast<double>(original.num_words()) / exact.num_words();
  EXPECT_NEAR(words_ratio, 1.0, 0.05);
  EXPECT_LT(original.MemoryBytes(), exact.MemoryBytes());
  // Stored rows too short for a scale and codes are refused.
  VocabularySnapshot bad = snapshot;
  bad.descriptors = cv::Mat(bad.descriptors.rows, 8, CV_8U, cv::Scalar(0));
  Vocabulary target(options);
  EXPECT_THROW(target.Import(bad), InputError);
}

TEST(VocabularySnapshot, EmptyVocabularyRoundTrips) {
  Vocabulary empty{VocabularyOptions()};
  const VocabularySnapshot s = empty.Export();
  EXPECT_TRUE(s.word_ids.empty());
  Vocabulary restored{VocabularyOptions()};
  restored.Import(s);
  EXPECT_EQ(restored.num_words(), 0u);
  EXPECT_EQ(restored.num_nodes(), 0u);
}

TEST(VocabularySnapshot, InconsistentSnapshotsAndNonEmptyTargetsThrow) {
  const SyntheticDescriptors gen = Generator(DescriptorKind::kBinary);
  Vocabulary original{VocabularyOptions()};
  Fill(&original, gen, DescriptorKind::kBinary);
  const VocabularySnapshot good = original.Export();
  auto import = [](const VocabularySnapshot& s) {
    Vocabulary v{VocabularyOptions()};
    v.Import(s);
  };
  EXPECT_NO_THROW(import(good));
  {  // into a vocabulary that already has nodes
    Vocabulary v{VocabularyOptions()};
    v.AddNode(1, RouteFrame(gen, 0, 1), DescriptorKind::kBinary);
    EXPECT_THROW(v.Import(good), InputError);
  }
  VocabularySnapshot s = good;
  s.descriptors = s.descriptors.rowRange(0, s.descriptors.rows - 1).clone();
  EXPECT_THROW(import(s), InputError);  // a word without descriptor
  s = good;
  std::swap(s.word_ids[0], s.word_ids[1]);
  EXPECT_THROW(import(s), InputError);  // ids not increasing
  s = good;
  s.next_word_id = s.word_ids.back();
  EXPECT_THROW(import(s), InputError);  // would reuse an id
  s = good;
  s.nodes[0].word_counts.push_back({s.next_word_id + 5, 1});
  EXPECT_THROW(import(s), InputError);  // reference to a missing word
  s = good;
  s.word_ids.push_back(s.next_word_id);
  s.descriptors.push_back(s.descriptors.row(0).clone());
  s.next_word_id += 1;
  EXPECT_THROW(import(s), InputError);  // a word referenced by no node
  s = good;
  s.descriptors.convertTo(s.descriptors, CV_32F);
  EXPECT_THROW(import(s), InputError);  // descriptor type vs kind
  s = good;
  s.nodes[1].word_counts[0].second = 0;
  EXPECT_THROW(import(s), InputError);  // zero occurrences
  s = good;
  s.next_word_id = kMaxWordId + 2;
  EXPECT_THROW(import(s), InputError);  // ids beyond what the dense tables accept
}

}  // namespace
}  // namespace duskmap
