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

namespace duskmap {
namespace {

// A map of 6 float nodes (the node descriptors do not matter here) and a
// vocabulary that quantized 6 frames, one of them a bad signature, then lost
// node 3 (graph reduction): gaps in the word ids, next id past them.
struct Fixture {
  Map map;
  VocabularySnapshot exported;
};

Fixture MakeFixture() {
  Fixture f;
  f.map = testing::MakeTestMap(3, 400, false);
  SyntheticDescriptorOptions o;
  o.kind = DescriptorKind::kFloat;
  o.cols = 64;
  const SyntheticDescriptors gen(o);
  Vocabulary vocabulary{VocabularyOptions()};
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
      (std::filesystem::temp_directory_path() / "duskmap_map_vocabulary_test.db").string();
  SaveMap(f.map, path);
  const Map loaded = LoadMap(path);
  std::remove(path.c_str());
  EXPECT_TRUE(MapVocabularySnapshot(loaded) == f.exported);
}

TEST(MapVocabulary, ASnapshotNamingAMissingNodeIsAnError) {
  Fixture f = MakeFixture();
  VocabularySnapshot bad = f.exported;
  bad.nodes.push_back({42, 10, {}});
  EXPECT_THROW(SetMapVocabulary(bad, &f.map), InputError);
}

}  // namespace
}  // namespace duskmap
