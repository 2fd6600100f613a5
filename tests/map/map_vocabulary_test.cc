#include "slam/map/map_vocabulary.h"

#include <cstdio>
#include <filesystem>
#include <numeric>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/map/map_store.h"
#include "slam/vocabulary/synthetic_descriptors.h"
#include "slam/vocabulary/vocabulary.h"
#include "tests/map/test_map.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

// A map of 6 float nodes (the node descriptors do not matter here) and a
// vocabulary that quantized 6 frames, one of them a bad signature, then lost
// node 3 (graph reduction): gaps in the word ids, next id past them.
struct Fixture {
  Map map;
  VocabularySnapshot exported;
};

Fixture MakeFixture(DescriptorStorage word_storage = DescriptorStorage::kFloat32) {
  Fixture f;
  f.map = testing::MakeTestMap(3, 400, false);
  f.map.mutable_metadata().word_storage = word_storage;
  SyntheticDescriptorOptions o;
  o.kind = DescriptorKind::kFloat;
  o.cols = 64;
  const SyntheticDescriptors gen(o);
  VocabularyOptions options;
  options.index.float_storage = word_storage;
  Vocabulary vocabulary(options);
  for (NodeId n = 1; n <= 5; ++n) {
    std::vector<int64_t> ids(400);
    std::iota(ids.begin(), ids.end(), 50 * n);
    vocabulary.AddNode(n, gen.Observe(ids, 0, 1.0, n), DescriptorKind::kFloat);
  }
  vocabulary.AddNode(6, gen.Random(30, 9), DescriptorKind::kFloat);  // bad signature
  vocabulary.RemoveNode(3);
  f.map.RemoveNode(3);
  f.exported = vocabulary.Export();
  return f;
}

TEST(MapVocabulary, TheMapHoldsTheVocabularyExactly) {
  Fixture f = MakeFixture();
  SetMapVocabulary(f.exported, &f.map);
  EXPECT_EQ(f.map.words().next_word_id, f.exported.next_word_id);
  EXPECT_TRUE(MapVocabularySnapshot(f.map) == f.exported);
  // The bad-signature node is kept with n_j and no words.
  EXPECT_TRUE(f.map.node(6).word_ids.empty());
  EXPECT_EQ(f.map.node(6).vocabulary_features, 30);
  // Restored into a vocabulary it exports the same snapshot again.
  Vocabulary restored{VocabularyOptions()};
  restored.Import(MapVocabularySnapshot(f.map));
  EXPECT_TRUE(restored.Export() == f.exported);
}

TEST(MapVocabulary, SurvivesSaveAndLoad) {
  Fixture f = MakeFixture();
  SetMapVocabulary(f.exported, &f.map);
  const std::string path =
      testing::ProcessTempPath("map_vocabulary.db");
  SaveMap(f.map, path);
  const Map loaded = LoadMap(path);
  std::remove(path.c_str());
  EXPECT_TRUE(MapVocabularySnapshot(loaded) == f.exported);
}

// Quantized words are stored as the vocabulary keeps them (offset, step,
// codes): save and load give back the same snapshot, the store checks the
// row width against the recorded storage, and a map that records float
// words refuses quantized ones.
TEST(MapVocabulary, QuantizedWordsSurviveSaveAndLoad) {
  Fixture f = MakeFixture(DescriptorStorage::kUint8);
  SetMapVocabulary(f.exported, &f.map);
  EXPECT_EQ(f.map.words().descriptors.cols, 64 + 8);
  const std::string path =
      testing::ProcessTempPath("map_vocabulary_quantized.db");
  SaveMap(f.map, path);
  const Map loaded = LoadMap(path);
  EXPECT_EQ(loaded.metadata().word_storage, DescriptorStorage::kUint8);
  EXPECT_TRUE(MapVocabularySnapshot(loaded) == f.exported);
  Vocabulary restored{VocabularyOptions()};
  restored.Import(MapVocabularySnapshot(loaded));
  EXPECT_TRUE(restored.Export() == f.exported);
  // The recorded storage says float32: the stored rows have the wrong width.
  testing::ExecuteSqlResealed(path, "UPDATE meta SET value = 'float32' WHERE key = 'word_storage'");
  EXPECT_THROW(LoadMap(path), InputError);
  std::remove(path.c_str());
  Fixture float_map = MakeFixture();
  EXPECT_THROW(SetMapVocabulary(f.exported, &float_map.map), InputError);
}

TEST(MapVocabulary, ASnapshotNamingAMissingNodeIsAnError) {
  Fixture f = MakeFixture();
  VocabularySnapshot bad = f.exported;
  bad.nodes.push_back({42, 10, {}});
  EXPECT_THROW(SetMapVocabulary(bad, &f.map), InputError);
}

}  // namespace
}  // namespace duskmap
