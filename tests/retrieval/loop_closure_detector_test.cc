#include "slam/retrieval/loop_closure_detector.h"

#include <numeric>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/vocabulary/synthetic_descriptors.h"

namespace duskmap {
namespace {

std::vector<int64_t> Window(int64_t first, int count) {
  std::vector<int64_t> ids(count);
  std::iota(ids.begin(), ids.end(), first);
  return ids;
}

class LcdTest : public ::testing::TestWithParam<DescriptorKind> {
 protected:
  LcdTest() : gen_(Options(GetParam())) {}
  static SyntheticDescriptorOptions Options(DescriptorKind kind) {
    SyntheticDescriptorOptions o;
    o.kind = kind;
    o.cols = kind == DescriptorKind::kFloat ? 128 : 32;
    return o;
  }
  // 40 landmarks drawn from 1000 generic ones seen everywhere (so that, as
  // with real images, many places share a few words with any frame).
  static std::vector<int64_t> Generic(uint64_t seed) {
    Rng rng(seed);
    std::vector<int64_t> ids;
    for (int i = 0; i < 40; ++i) ids.push_back(50000000 + static_cast<int64_t>(rng() % 1000));
    return ids;
  }
  // Place k of the route sees landmarks [200 k, 200 k + 360) and 40 generic ones.
  FrameFeatures Place(int k, uint64_t seed) const {
    std::vector<int64_t> ids = Window(200 * k, 360);
    const std::vector<int64_t> generic = Generic(seed);
    ids.insert(ids.end(), generic.begin(), generic.end());
    return gen_.ToFeatures(gen_.Observe(ids, 0, 1.0, seed));
  }
  FrameFeatures Unseen(uint64_t seed) const {
    std::vector<int64_t> ids = Window(20000000 + 400 * static_cast<int64_t>(seed), 360);
    const std::vector<int64_t> generic = Generic(seed);
    ids.insert(ids.end(), generic.begin(), generic.end());
    return gen_.ToFeatures(gen_.Observe(ids, 0, 1.0, seed));
  }

  // Maps places 0..n-1 as nodes 1..n of session 0.
  // Returns the frames accepted as loops (expected: none after the filter's
  // start-up, see docs/loop_closure.md).
  std::vector<int> MapRoute(LoopClosureDetector* lcd, int n) const {
    std::vector<int> accepted;
    for (int k = 0; k < n; ++k) {
      const LcdResult r = lcd->AddAndDetect(k + 1, 0, Place(k, k));
      if (k > 0) lcd->graph().AddLink(k, k + 1, LinkType::kOdometry);
      if (r.accepted()) accepted.push_back(k);
    }
    return accepted;
  }
  SyntheticDescriptors gen_;
};

TEST_P(LcdTest, RevisitRaisesTheCorrectHypothesisWithinAFewFrames) {
  LoopClosureDetector lcd{LoopClosureOptions()};
  for (int k : MapRoute(&lcd, 40)) EXPECT_LT(k, 16) << "false loop after the start-up";
  // Drive the route again from its start: new nodes 41.. revisit places 0...
  int first_accepted = -1;
  for (int k = 0; k < 6; ++k) {
    const NodeId node = 41 + k;
    const LcdResult r = lcd.AddAndDetect(node, 0, Place(k, 1000 + k));
    lcd.graph().AddLink(node - 1, node, LinkType::kOdometry);
    if (r.accepted()) {
      EXPECT_NEAR(r.hypothesis, k + 1, 1) << "frame " << k;
      EXPECT_GE(r.score, 0.11);
      if (first_accepted < 0) first_accepted = k;
    }
  }
  EXPECT_GE(first_accepted, 0);
  EXPECT_LE(first_accepted, 2);
}

TEST_P(LcdTest, LocalizationDetectsWithoutChangingTheMap) {
  LoopClosureDetector lcd{LoopClosureOptions()};
  for (int k = 0; k < 30; ++k) {
    lcd.AddMapNode(k + 1, 0, Place(k, k));
    if (k > 0) lcd.graph().AddLink(k, k + 1, LinkType::kOdometry);
  }
  const size_t words = lcd.vocabulary().num_words();
  const size_t bytes = lcd.vocabulary().MemoryBytes();
  const size_t nodes = lcd.graph().size();
  int accepted = 0;
  for (int k = 10; k < 14; ++k) {
    const LcdResult r = lcd.Localize(Place(k, 500 + k));
    if (r.accepted()) {
      ++accepted;
      EXPECT_NEAR(r.hypothesis, k + 1, 1);
    }
    EXPECT_GT(r.num_words, 300);
    EXPECT_EQ(r.new_words, lcd.vocabulary().num_words() == words ? r.new_words : -1);
  }
  EXPECT_GE(accepted, 3);
  EXPECT_EQ(lcd.vocabulary().num_words(), words);
  EXPECT_EQ(lcd.vocabulary().MemoryBytes(), bytes);
  EXPECT_EQ(lcd.vocabulary().num_nodes(), 30u);
  EXPECT_EQ(lcd.graph().size(), nodes);
}

// A frame in new territory that shares `shared` of its 400 landmarks with
// place 12 (node 13). Weak similarity never makes a loop. With the reference's
// normalisation (§3.4) a single strong outlier is accepted on its own frame
// (measured: 20 shared -> 0.115 float / 0.108 binary, 100 -> 0.145; a true
// revisit's first frame: 0.154), but the hypothesis dies the next frame,
// whereas a true revisit keeps rising (see the revisit test).
TEST_P(LcdTest, ASingleSpuriousSimilarFrameIsNotALoop) {
  for (int shared : {10, 100}) {
    SCOPED_TRACE(shared);
    LoopClosureDetector lcd{LoopClosureOptions()};
    for (int k : MapRoute(&lcd, 40)) EXPECT_LT(k, 16) << "false loop after the start-up";
    NodeId node = 41;
    for (int k = 0; k < 8; ++k, ++node) {
      FrameFeatures f = Unseen(2000 + k);
      if (k == 4) {
        std::vector<int64_t> mix = Window(200 * 12, shared);
        const std::vector<int64_t> fresh = Window(10000000, 360 - shared);
        const std::vector<int64_t> generic = Generic(77);
        mix.insert(mix.end(), fresh.begin(), fresh.end());
        mix.insert(mix.end(), generic.begin(), generic.end());
        f = gen_.ToFeatures(gen_.Observe(mix, 0, 1.0, 77));
      }
      const LcdResult r = lcd.AddAndDetect(node, 0, f);
      lcd.graph().AddLink(node - 1, node, LinkType::kOdometry);
      if (k == 4) {  // place 12 is the most similar place
        EXPECT_NEAR(r.hypothesis, 13, 1);
        EXPECT_GT(lcd.last_likelihood().Raw(13), lcd.last_likelihood().mean);
      }
      if (shared <= 10 || k != 4) {
        EXPECT_FALSE(r.accepted()) << "frame " << k << " score " << r.score;
      }
    }
  }
}

// While the route is being revisited (the filter confident in the true
// place), one frame shares half of its landmarks with a far place (place 30,
// node 31) and none with the current one. That single frame must not make
// node 31 (or its neighbours) an accepted loop, and the revisit goes on
// being detected at the right places right after it.
TEST_P(LcdTest, ASingleSpuriousFrameDuringARevisitDoesNotMoveTheLoop) {
  LoopClosureDetector lcd{LoopClosureOptions()};
  for (int k : MapRoute(&lcd, 40)) EXPECT_LT(k, 16) << "false loop after the start-up";
  int accepted_after = 0;
  for (int k = 0; k < 8; ++k) {
    const NodeId node = 41 + k;
    FrameFeatures f = Place(k, 3000 + k);
    if (k == 4) {
      std::vector<int64_t> mix = Window(200 * 30, 200);
      const std::vector<int64_t> fresh = Window(30000000, 160);
      const std::vector<int64_t> generic = Generic(78);
      mix.insert(mix.end(), fresh.begin(), fresh.end());
      mix.insert(mix.end(), generic.begin(), generic.end());
      f = gen_.ToFeatures(gen_.Observe(mix, 0, 1.0, 78));
    }
    const LcdResult r = lcd.AddAndDetect(node, 0, f);
    lcd.graph().AddLink(node - 1, node, LinkType::kOdometry);
    if (k == 4) {
      EXPECT_GT(lcd.last_likelihood().Raw(31), lcd.last_likelihood().mean);  // it is similar
    }
    if (r.accepted()) {
      EXPECT_LE(std::abs(r.hypothesis - (k + 1)), 2) << "frame " << k << " score " << r.score;
      if (k > 4) ++accepted_after;
    }
  }
  EXPECT_GE(accepted_after, 2);
}

// A map's vocabulary exported and imported (instead of re-quantizing the
// node descriptors) localizes exactly like the original detector (search
// made exhaustive so that the freshly built trees cannot differ in lookups).
TEST_P(LcdTest, ImportedMapLocalizesLikeTheOriginal) {
  LoopClosureOptions options;
  options.vocabulary.index.checks = 1000000;
  LoopClosureDetector original(options);
  for (int k = 0; k < 12; ++k) {
    original.AddMapNode(k + 1, k < 6 ? 0 : 1, Place(k, k));
    if (k > 0) original.graph().AddLink(k, k + 1, LinkType::kOdometry);
  }
  LoopClosureDetector restored(options);
  restored.ImportMap(original.vocabulary().Export(), [](NodeId n) { return n <= 6 ? 0 : 1; });
  for (int k = 1; k < 12; ++k) restored.graph().AddLink(k, k + 1, LinkType::kOdometry);
  EXPECT_EQ(restored.vocabulary().num_words(), original.vocabulary().num_words());
  EXPECT_EQ(restored.filter().num_places(), 12u);
  for (int k = 4; k < 8; ++k) {
    const LcdResult a = original.Localize(Place(k, 500 + k));
    const LcdResult b = restored.Localize(Place(k, 500 + k));
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.hypothesis, b.hypothesis);
    EXPECT_DOUBLE_EQ(a.score, b.score);
    EXPECT_EQ(a.num_words, b.num_words);
  }
  EXPECT_THROW(restored.ImportMap(original.vocabulary().Export(), [](NodeId) { return 0; }), InputError);
}

TEST_P(LcdTest, BadFramesEmptyMapsAndRemovals) {
  LoopClosureDetector lcd{LoopClosureOptions()};
  // Empty map.
  EXPECT_EQ(lcd.Localize(Place(0, 1)).status, LcdStatus::kNoCandidates);
  // One-node map: an identical frame cannot be accepted (reference rule).
  lcd.AddMapNode(1, 0, Place(0, 1));
  const LcdResult single = lcd.Localize(Place(0, 2));
  EXPECT_EQ(single.status, LcdStatus::kRejectedSinglePlace);
  EXPECT_EQ(single.hypothesis, 1);
  for (int k = 1; k < 20; ++k) {
    lcd.AddMapNode(k + 1, 0, Place(k, k));
    lcd.graph().AddLink(k, k + 1, LinkType::kOdometry);
  }
  lcd.Localize(Place(7, 3));
  const double virtual_before = lcd.filter().VirtualPosterior();
  const double p8 = lcd.filter().Posterior(8);
  // No features, or fewer than 200: marked and skipped, the filter untouched.
  EXPECT_EQ(lcd.Localize(FrameFeatures()).status, LcdStatus::kBadSignature);
  EXPECT_EQ(lcd.Localize(gen_.ToFeatures(gen_.Random(120, 4))).status, LcdStatus::kBadSignature);
  EXPECT_EQ(lcd.filter().VirtualPosterior(), virtual_before);
  EXPECT_EQ(lcd.filter().Posterior(8), p8);
  // Removal, twice.
  const NodeRemoval once = lcd.RemoveNode(8);
  EXPECT_TRUE(once.was_present);
  EXPECT_FALSE(lcd.IsCandidate(8));
  const NodeRemoval twice = lcd.RemoveNode(8);
  EXPECT_FALSE(twice.was_present);
  EXPECT_TRUE(twice.removed_words.empty());
  const LcdResult after = lcd.Localize(Place(7, 4));
  EXPECT_NE(after.hypothesis, 8);
  EXPECT_THROW(lcd.AddMapNode(3, 0, Place(3, 3)), InputError);
  EXPECT_THROW(lcd.AddAndDetect(0, 0, Place(3, 3)), InputError);
}

TEST_P(LcdTest, ShortTermMemoryIsNotACandidate) {
  LoopClosureDetector lcd{LoopClosureOptions()};
  for (int k = 0; k < 12; ++k) {
    const LcdResult r = lcd.AddAndDetect(k + 1, 0, Place(0, k));  // the same place, 12 times
    if (k > 0) lcd.graph().AddLink(k, k + 1, LinkType::kOdometry);
    if (k < 10) {
      EXPECT_EQ(r.status, LcdStatus::kNoCandidates);
    }
  }
  EXPECT_EQ(lcd.filter().num_places(), 2u);  // 12 nodes, STM of 10
  lcd.StartNewSession();
  EXPECT_EQ(lcd.filter().num_places(), 12u);
}

INSTANTIATE_TEST_SUITE_P(Kinds, LcdTest,
                         ::testing::Values(DescriptorKind::kFloat, DescriptorKind::kBinary),
                         [](const auto& info) {
                           return info.param == DescriptorKind::kFloat ? "Float" : "Binary";
                         });

TEST(LoopClosureOptions, Check) {
  LoopClosureOptions o;
  o.loop_threshold = 2.0;
  EXPECT_THROW(o.Check(), ConfigError);
  o = LoopClosureOptions();
  o.short_term_memory_size = -1;
  EXPECT_THROW(LoopClosureDetector{o}, ConfigError);
  EXPECT_STREQ(LcdStatusName(LcdStatus::kBadSignature), "bad_signature");
}

}  // namespace
}  // namespace duskmap
