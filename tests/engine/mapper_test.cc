// The Mapper on its own, frame by frame, on the tiny synthetic dataset: a
// node per frame linked by odometry within its session, a same-light session
// merged into the map by a loop closure, and loops refused when registration
// cannot accept them.
#include "slam/engine/mapper.h"

#include <gtest/gtest.h>

#include "slam/io/synthetic_dataset.h"
#include "tests/engine/tiny_dataset.h"

namespace duskmap {
namespace {

// The paper's settings without graph reduction: every frame stays a node.
EngineOptions PaperOptions() {
  EngineOptions options =
      ReadEngineOptionsFile(std::string(DUSKMAP_SOURCE_DIR) + "/configs/engine_paper.json");
  options.mapping.reduce_graph = false;
  return options;
}

// Replays `sessions` of the tiny dataset into `mapper`; the results of every frame.
std::vector<MappingFrameResult> Replay(Mapper* mapper, const std::vector<std::string>& sessions) {
  const std::unique_ptr<DatasetReader> dataset = OpenSyntheticDataset(testing::TinyDatasetPath());
  std::vector<MappingFrameResult> results;
  for (const std::string& name : sessions) {
    std::unique_ptr<SessionReader> reader = dataset->OpenSession(name);
    mapper->StartSession(name, reader->info().clock_time);
    while (std::optional<RgbdFrame> frame = reader->Next()) results.push_back(mapper->ProcessFrame(*frame));
  }
  return results;
}

TEST(MapperTest, EveryFrameIsANodeLinkedByOdometryToThePreviousOne) {
  Mapper mapper(PaperOptions());
  const std::vector<MappingFrameResult> results = Replay(&mapper, {"1"});
  ASSERT_EQ(results.size(), 25u);
  EXPECT_EQ(mapper.map().nodes().size(), 25u);
  EXPECT_EQ(results[0].lcd_status, LcdStatus::kNoCandidates);  // nothing to compare with yet
  EXPECT_GT(results[0].num_features, 100);
  for (size_t i = 1; i < results.size(); ++i) {
    EXPECT_EQ(results[i].session, results[0].session);
    EXPECT_GT(results[i].node, results[i - 1].node);
    const auto link = mapper.map().links().find({results[i - 1].node, results[i].node});
    ASSERT_NE(link, mapper.map().links().end()) << "frame " << i;
    EXPECT_EQ(link->second.type, LinkType::kOdometry);
  }
  const Map map = mapper.Finish();
  EXPECT_EQ(map.sessions().size(), 1u);
  EXPECT_FALSE(map.words().ids.empty());  // Finish stores the vocabulary's words
}

TEST(MapperTest, ASameLightSessionIsMergedByALoopClosure) {
  Mapper mapper(PaperOptions());
  const std::vector<MappingFrameResult> results = Replay(&mapper, {"1", "2"});
  int loops = 0, accepted_hypotheses = 0;
  for (size_t i = 25; i < results.size(); ++i) {
    loops += results[i].loop_closures_added;
    accepted_hypotheses += results[i].lcd_status == LcdStatus::kAccepted;
  }
  EXPECT_GT(accepted_hypotheses, 0);
  EXPECT_GT(loops, 0);
  bool crosses = false;
  for (const auto& [ends, link] : mapper.map().links()) {
    crosses |= link.type == LinkType::kLoopClosure &&
               mapper.map().node(ends.first).session != mapper.map().node(ends.second).session;
  }
  EXPECT_TRUE(crosses);
  const Map map = mapper.Finish();
  EXPECT_EQ(map.ConnectedSessionGroups().size(), 1u);
}

TEST(MapperTest, LoopsThatRegistrationRefusesAreNotAdded) {
  EngineOptions options = PaperOptions();
  options.registration.min_inliers = 5000;  // more than a frame has features
  Mapper mapper(options);
  const std::vector<MappingFrameResult> results = Replay(&mapper, {"1", "2"});
  int registrations = 0, links = 0;
  for (const MappingFrameResult& r : results) {
    registrations += r.registrations;
    links += r.loop_closures_added + r.proximity_links_added;
  }
  EXPECT_GT(registrations, 0);  // hypotheses were tried ...
  EXPECT_EQ(links, 0);          // ... and none accepted
  const Map map = mapper.Finish();
  EXPECT_EQ(map.ConnectedSessionGroups().size(), 2u);
}

}  // namespace
}  // namespace duskmap
