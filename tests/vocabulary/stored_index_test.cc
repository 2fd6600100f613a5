// The vocabulary index stored as bytes (DescriptorIndex::SaveState, the
// snapshot's index_state): restored, it equals a fresh build in every
// search, in its future growth and in its bytes; a state that does not fit
// falls back to a build and says why.
#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "slam/vocabulary/synthetic_descriptors.h"
#include "slam/vocabulary/vocabulary.h"

namespace duskmap {
namespace {

struct Case {
  const char* name;
  DescriptorKind kind;
  DescriptorStorage storage;
  BinaryDistance binary_distance = BinaryDistance::kHamming;
};

const Case kCases[] = {
    {"float32", DescriptorKind::kFloat, DescriptorStorage::kFloat32},
    {"quantized", DescriptorKind::kFloat, DescriptorStorage::kUint8},
    {"binary", DescriptorKind::kBinary, DescriptorStorage::kFloat32},
    {"binary_byte_l1", DescriptorKind::kBinary, DescriptorStorage::kFloat32,
     BinaryDistance::kByteL1}};

SyntheticDescriptors Generator(DescriptorKind kind) {
  SyntheticDescriptorOptions o;
  o.kind = kind;
  o.cols = kind == DescriptorKind::kFloat ? 64 : 32;
  return SyntheticDescriptors(o);
}

cv::Mat Frame(const SyntheticDescriptors& gen, int k, uint64_t seed) {
  std::vector<int64_t> ids(400);
  std::iota(ids.begin(), ids.end(), 150 * k);
  return gen.Observe(ids, 0, 1.0, seed);
}

VocabularyOptions Options(const Case& c) {
  VocabularyOptions o;
  o.index.float_storage = c.storage;
  o.index.binary_distance = c.binary_distance;
  o.index.checks = 16;  // few checks: results depend on the exact trees
  return o;
}

// The snapshot of a 12-node vocabulary and the index Import builds from it.
VocabularySnapshot StoredSnapshot(const Case& c) {
  const SyntheticDescriptors gen = Generator(c.kind);
  Vocabulary mapper(Options(c));
  for (int k = 0; k < 12; ++k) mapper.AddNode(k + 1, Frame(gen, k % 9, k), c.kind);
  VocabularySnapshot snapshot = mapper.Export();
  Vocabulary built(Options(c));
  built.Import(snapshot);
  EXPECT_FALSE(built.index_restore().restored);
  EXPECT_EQ(built.index_restore().rebuild_reason, "no stored index");
  snapshot.index_state = built.SaveIndexState();
  EXPECT_FALSE(snapshot.index_state.empty());
  return snapshot;
}

TEST(StoredIndex, RestoredIndexEqualsAFreshBuild) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    const VocabularySnapshot stored = StoredSnapshot(c);
    VocabularySnapshot plain = stored;
    plain.index_state.clear();
    Vocabulary built(Options(c));
    built.Import(plain);
    Vocabulary restored(Options(c));
    restored.Import(stored);
    ASSERT_TRUE(restored.index_restore().restored) << restored.index_restore().rebuild_reason;
    EXPECT_EQ(restored.SaveIndexState(), stored.index_state);
    EXPECT_EQ(restored.MemoryBytes(), built.MemoryBytes());
    const SyntheticDescriptors gen = Generator(c.kind);
    for (int k = 0; k < 6; ++k) {
      const cv::Mat query = k < 3 ? Frame(gen, k + 2, 1000 + k) : gen.Random(300, 50 + k);
      EXPECT_EQ(restored.Quantize(query, c.kind).words, built.Quantize(query, c.kind).words);
    }
    // Growing them the same way (insertions, then a rebuild on doubling)
    // keeps them equal: the random generator's state was restored too.
    for (int k = 0; k < 14; ++k) {
      const cv::Mat frame = Frame(gen, 20 + k, 2000 + k);
      ASSERT_EQ(restored.AddNode(100 + k, frame, c.kind).words,
                built.AddNode(100 + k, frame, c.kind).words);
    }
    EXPECT_GT(built.index_rebuilds(), 1);
    EXPECT_EQ(restored.index_rebuilds(), built.index_rebuilds());
    EXPECT_EQ(restored.SaveIndexState(), built.SaveIndexState());
  }
}

TEST(StoredIndex, StateThatDoesNotFitIsRebuiltWithTheReason) {
  const Case& c = kCases[2];
  const VocabularySnapshot stored = StoredSnapshot(c);
  VocabularySnapshot plain = stored;
  plain.index_state.clear();
  Vocabulary reference(Options(c));
  reference.Import(plain);
  const std::vector<uint8_t> expected = reference.SaveIndexState();

  auto rebuilt_reason = [&](const VocabularySnapshot& snapshot, const VocabularyOptions& options) {
    Vocabulary v(options);
    v.Import(snapshot);
    EXPECT_FALSE(v.index_restore().restored);
    if (options.index.seed == Options(c).index.seed) {
      EXPECT_EQ(v.SaveIndexState(), expected);
    }
    return v.index_restore().rebuild_reason;
  };
  VocabularySnapshot truncated = stored;
  truncated.index_state.resize(truncated.index_state.size() / 2);
  EXPECT_NE(rebuilt_reason(truncated, Options(c)).find("truncated"), std::string::npos);

  VocabularySnapshot trailing = stored;
  trailing.index_state.push_back(0);
  EXPECT_NE(rebuilt_reason(trailing, Options(c)).find("trailing"), std::string::npos);

  VocabularyOptions other_seed = Options(c);
  other_seed.index.seed = 7;
  EXPECT_NE(rebuilt_reason(stored, other_seed).find("other options"), std::string::npos);
  VocabularyOptions other_distance = Options(c);
  other_distance.index.binary_distance = BinaryDistance::kByteL1;
  {
    Vocabulary v(other_distance);
    v.Import(stored);
    EXPECT_FALSE(v.index_restore().restored);
    EXPECT_NE(v.index_restore().rebuild_reason.find("binary distance hamming"), std::string::npos)
        << v.index_restore().rebuild_reason;
  }

  VocabularySnapshot other_words = stored;  // one word fewer than the state names
  other_words.word_ids.pop_back();
  other_words.descriptors = other_words.descriptors.rowRange(0, other_words.descriptors.rows - 1).clone();
  for (VocabularyNodeWords& n : other_words.nodes) {
    auto& wc = n.word_counts;
    wc.erase(std::remove_if(wc.begin(), wc.end(),
                            [&](const auto& w) { return w.first == stored.word_ids.back(); }),
             wc.end());
  }
  {
    Vocabulary v(Options(c));
    v.Import(other_words);
    EXPECT_FALSE(v.index_restore().restored);
    EXPECT_NE(v.index_restore().rebuild_reason.find("words"), std::string::npos)
        << v.index_restore().rebuild_reason;
  }

  VocabularySnapshot flagged = stored;  // the map store could not read it
  flagged.index_state_problem = "map.db: the stored vocabulary index fails its checksum";
  EXPECT_EQ(rebuilt_reason(flagged, Options(c)), flagged.index_state_problem);

  // A structure that points outside itself is refused, not searched.
  VocabularySnapshot damaged = stored;
  for (size_t i = damaged.index_state.size() / 2; i < damaged.index_state.size() - 7000; i += 4) {
    damaged.index_state[i] = 0xff;
    damaged.index_state[i + 1] = 0xff;
    damaged.index_state[i + 2] = 0xff;
    damaged.index_state[i + 3] = 0x7f;
  }
  EXPECT_FALSE(rebuilt_reason(damaged, Options(c)).empty());
}

}  // namespace
}  // namespace duskmap
