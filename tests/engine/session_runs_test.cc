// End-to-end tests of the engine on tiny synthetic sessions (the issue's
// list): same-light re-localization, the day/night effect, merging, graph
// reduction, and store round trip with a read-only map.
#include "slam/engine/session_runs.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include <gtest/gtest.h>

#include "slam/eval/trajectory_error.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/engine/record_io.h"
#include "slam/map/map_store.h"
#include "slam/map/sqlite_db.h"
#include "tests/engine/tiny_dataset.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

// The paper's settings (configs/engine_paper.json).
EngineOptions TestOptions() {
  return ReadEngineOptionsFile(std::string(DUSKMAP_SOURCE_DIR) + "/configs/engine_paper.json");
}

class EngineSessions : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_ = OpenSyntheticDataset(testing::TinyDatasetPath()).release();
  }
  static void TearDownTestSuite() {
    delete dataset_;
    dataset_ = nullptr;
  }
  // Maps are built once per process and shared by the tests.
  static const MappingRun& MapOf(const std::string& label, std::vector<std::string> sessions,
                                 bool reduce) {
    static std::map<std::string, MappingRun> cache;
    auto it = cache.find(label);
    if (it == cache.end()) {
      EngineOptions options = TestOptions();
      options.mapping.reduce_graph = reduce;
      it = cache.emplace(label, BuildMap(*dataset_, sessions, options)).first;
    }
    return it->second;
  }
  static LocalizationRun Localize(const Map& map, const std::string& session) {
    std::unique_ptr<SessionReader> reader = dataset_->OpenSession(session);
    return LocalizeSession(map, *reader, TestOptions());
  }
  static DatasetReader* dataset_;
};

DatasetReader* EngineSessions::dataset_ = nullptr;

// Expects no wrong re-localization and names each wrong one.
void ExpectNoWrong(const LocalizationRun& run, const std::string& what) {
  EXPECT_EQ(run.summary.relocalization.num_wrong, 0) << what;
  for (const LocalizationRecord& r : run.records) {
    if (r.check && !r.check->correct) {
      ADD_FAILURE() << what << ": frame " << r.frame_index << " wrong by "
                    << r.check->error.translation_m << " m, " << r.check->error.rotation_deg
                    << " deg (node " << r.matched_node << " by " << LinkTypeName(r.matched_by)
                    << ", " << r.inliers << " inliers)";
    }
  }
}

// "outcome/registration status: count, ..." for failure messages.
std::string Outcomes(const LocalizationRun& run) {
  std::map<std::string, int> counts;
  for (const LocalizationRecord& r : run.records) {
    std::string key = LocalizationOutcomeName(r.outcome);
    key += std::string("/") + LcdStatusName(r.lcd_status);
    if (r.registration_status) key += std::string("/") + RegistrationStatusName(*r.registration_status);
    if (r.cache_validation) key += std::string("/cache ") + CacheValidationName(*r.cache_validation);
    ++counts[key];
  }
  std::string text;
  for (const auto& [key, n] : counts) text += key + ": " + std::to_string(n) + "; ";
  return text;
}

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The first engine test: a single-session map localizes a session
// recorded minutes later at the same light, >= 90 % of frames, none wrong.
TEST_F(EngineSessions, SameLightSessionRelocalizes) {
  const MappingRun& map1 = MapOf("1", {"1"}, false);
  const LocalizationRun run = Localize(map1.map, "A");
  const RelocalizationSummary& s = run.summary.relocalization;
  EXPECT_TRUE(run.summary.evaluated);
  std::cout << "[ measured ] map 1, session A: " << s.num_relocalized << " of " << s.num_frames
            << " re-localized, " << s.num_wrong << " wrong\n";
  EXPECT_GE(s.relocalized_pct, 90.0) << s.num_relocalized << " of " << s.num_frames << ": "
                                     << Outcomes(run);
  ExpectNoWrong(run, "map 1, session A");
}

// The reference's odometry-cache validation (spec §9.2): the first accepted
// transform of the session only enters the cache (one re-localization alone
// is never applied), later ones are applied when consistent; none is wrong.
TEST_F(EngineSessions, OdometryCacheDelaysAndValidatesRelocalizations) {
  EngineOptions options = TestOptions();
  options.localization.odometry_cache_size = 10;
  std::unique_ptr<SessionReader> reader = dataset_->OpenSession("A");
  const LocalizationRun run = LocalizeSession(MapOf("1", {"1"}, false).map, *reader, options);
  const LocalizationRecord* first_accepted = nullptr;
  for (const LocalizationRecord& r : run.records) {
    if (r.cache_validation) {
      first_accepted = &r;
      break;
    }
  }
  ASSERT_NE(first_accepted, nullptr) << Outcomes(run);
  EXPECT_EQ(first_accepted->outcome, LocalizationOutcome::kOdometryCacheWaiting);
  EXPECT_FALSE(first_accepted->relocalized);
  EXPECT_FALSE(first_accepted->map_from_camera.has_value());
  EXPECT_GE(run.summary.relocalization.num_relocalized, 10) << Outcomes(run);
  for (const LocalizationRecord& r : run.records) {
    if (r.relocalized) {
      EXPECT_EQ(r.cache_validation, CacheValidation::kApplied);
    }
  }
  ExpectNoWrong(run, "map 1, session A, odometry cache 10");
}

// Expects at most `max_wrong` wrong re-localizations, each a near miss: within
// 0.5 m and 10 degrees of the truth (the check's 0.5 m / 5 degrees draws
// the line between right and wrong; a gross error is a different failure).
void ExpectOnlyNearMisses(const LocalizationRun& run, const std::string& what, int max_wrong) {
  EXPECT_LE(run.summary.relocalization.num_wrong, max_wrong) << what;
  for (const LocalizationRecord& r : run.records) {
    if (r.check && !r.check->correct) {
      EXPECT_TRUE(r.check->error.translation_m < 0.5 && r.check->error.rotation_deg < 10.0)
          << what << ": frame " << r.frame_index << " wrong by " << r.check->error.translation_m
          << " m, " << r.check->error.rotation_deg << " deg";
    }
  }
}

TEST_F(EngineSessions, NightSessionNeedsANightMap) {
  const LocalizationRun day_only = Localize(MapOf("1", {"1"}, false).map, "F");
  const LocalizationRun day_night = Localize(MapOf("1+6", {"1", "6"}, false).map, "F");
  // The day map on the night session accepts one near miss with SURF as
  // OpenCV computes it (2026-12-06: frame 12, 0.34 m and 7.0 degrees off, 38
  // inliers, by proximity); the day+night map none.
  ExpectOnlyNearMisses(day_only, "map 1, session F", 1);
  ExpectNoWrong(day_night, "map 1+6, session F");
  std::cout << "[ measured ] session F: map 1 " << day_only.summary.relocalization.relocalized_pct
            << " %, map 1+6 " << day_night.summary.relocalization.relocalized_pct << " %\n";
  EXPECT_GE(day_night.summary.relocalization.relocalized_pct,
            day_only.summary.relocalization.relocalized_pct + 20.0)
      << "day map " << day_only.summary.relocalization.relocalized_pct << "%, day+night map "
      << day_night.summary.relocalization.relocalized_pct << "%";
}

TEST_F(EngineSessions, MergingTwoSessionsGivesOneAccurateMap) {
  const Map& map = MapOf("1+2", {"1", "2"}, false).map;
  EXPECT_EQ(map.ConnectedSessionGroups().size(), 1u);
  std::vector<Rigid3d> estimated, truth;
  for (const auto& [id, node] : map.nodes()) {
    ASSERT_TRUE(node.truth_from_camera.has_value());
    estimated.push_back(node.map_from_camera());
    truth.push_back(*node.truth_from_camera);
  }
  const AteResult ate = ComputeAte(estimated, truth);
  // "Within a few centimetres": measured 5.8 cm RMSE over 60 nodes.
  EXPECT_LT(ate.rmse_m, 0.08) << "ATE " << ate.rmse_m << " m over " << ate.num_poses << " nodes";
}

TEST_F(EngineSessions, GraphReductionShrinksRepeatedRouteAndStaysConnected) {
  const Map& full = MapOf("1+2", {"1", "2"}, false).map;
  const Map& reduced = MapOf("1-2", {"1", "2"}, true).map;
  EXPECT_LT(reduced.nodes().size(), full.nodes().size());
  EXPECT_LT(reduced.NodesOfSession(1).size(), full.NodesOfSession(1).size());
  EXPECT_EQ(reduced.ConnectedSessionGroups().size(), 1u);
  EXPECT_FALSE(reduced.NodesOfSession(1).empty());  // the session anchor stays
  for (const auto& [key, link] : reduced.links()) {
    EXPECT_TRUE(reduced.HasNode(link.from) && reduced.HasNode(link.to));
  }
}

TEST_F(EngineSessions, StoredMapLocalizesIdenticallyAndStaysUnchanged) {
  const Map& map = MapOf("1", {"1"}, false).map;
  const std::string dir = testing::ProcessTempDir("engine_maps");
  const std::string before = dir + "/before.db", after = dir + "/after.db";
  SaveMap(map, before);
  const LocalizationRun in_memory = Localize(map, "A");
  SaveMap(map, after);
  EXPECT_EQ(FileBytes(before), FileBytes(after)) << "localization modified the map";

  MapLoadOptions load_options;
  load_options.expected_feature_type = "surf";
  const Map loaded = LoadMap(before, load_options);
  const LocalizationRun from_file = Localize(loaded, "A");
  // The words loaded apart (as the experiment runner and `duskmap localize`
  // do): the same records, and the words counted once.
  MapLoadOptions apart = load_options;
  apart.load_words = false;
  const Map without_words = LoadMap(before, apart);
  EXPECT_TRUE(without_words.words().ids.empty());
  std::unique_ptr<SessionReader> reader = dataset_->OpenSession("A");
  const LocalizationRun words_apart =
      LocalizeSession(without_words, LoadMapWords(before, apart), *reader, TestOptions());
  const size_t stored_words_bytes =
      map.words().ids.size() * sizeof(WordId) +
      map.words().descriptors.total() * map.words().descriptors.elemSize();
  EXPECT_EQ(words_apart.memory.words_index_bytes + stored_words_bytes,
            from_file.memory.words_index_bytes);
  // As the runner and `duskmap localize` load it: the words apart and the
  // node rows that are words' rows shared with them (fewer bytes, same
  // records).
  MapAndWords shared = LoadMapAndWords(before, load_options);
  size_t shared_rows = 0;
  for (const auto& [id, node] : shared.map.nodes()) shared_rows += node.features.num_shared_rows();
  EXPECT_GT(shared_rows, 0u);
  const LocalizationRun rows_shared =
      LocalizeSession(shared.map, std::move(shared.words), *reader, TestOptions());
  EXPECT_LT(rows_shared.memory.descriptors_bytes, words_apart.memory.descriptors_bytes);
  EXPECT_EQ(rows_shared.memory.words_index_bytes, words_apart.memory.words_index_bytes);
  for (const LocalizationRun* other : {&from_file, &words_apart, &rows_shared}) {
    ASSERT_EQ(in_memory.records.size(), other->records.size());
    for (size_t i = 0; i < in_memory.records.size(); ++i) {
      const LocalizationRecord &a = in_memory.records[i], &b = other->records[i];
      EXPECT_EQ(a.relocalized, b.relocalized) << "frame " << i;
      EXPECT_EQ(a.matched_node, b.matched_node) << "frame " << i;
      EXPECT_EQ(a.inliers, b.inliers) << "frame " << i;
      ASSERT_EQ(a.map_from_camera.has_value(), b.map_from_camera.has_value());
      if (a.map_from_camera) {
        EXPECT_EQ(a.map_from_camera->translation, b.map_from_camera->translation) << "frame " << i;
      }
    }
  }
  std::filesystem::remove_all(dir);
}

// The records of two runs, timings aside, are identical.
void ExpectSameRecords(const LocalizationRun& a, const LocalizationRun& b, const std::string& what) {
  ASSERT_EQ(a.records.size(), b.records.size()) << what;
  for (size_t i = 0; i < a.records.size(); ++i) {
    nlohmann::json ja = LocalizationRecordToJson(a.records[i]);
    nlohmann::json jb = LocalizationRecordToJson(b.records[i]);
    ja.erase("timings_ms");
    jb.erase("timings_ms");
    ASSERT_EQ(ja, jb) << what << ", frame " << i;
  }
  EXPECT_EQ(a.memory.words_index_bytes, b.memory.words_index_bytes) << what;
}

TEST_F(EngineSessions, StoredIndexIsRestoredAndLocalizesAsABuiltOne) {
  const MappingRun& built = MapOf("1+6", {"1", "6"}, false);
  ASSERT_FALSE(built.map.words().index_state.empty());
  const std::string dir = testing::ProcessTempDir("engine_index");
  const std::string path = dir + "/map.db";
  SaveMap(built.map, path);
  const std::string saved = FileBytes(path);
  const EngineOptions options = TestOptions();
  std::unique_ptr<SessionReader> reader = dataset_->OpenSession("F");

  MapAndWords loaded = LoadMapAndWords(path, options.LocalizationMapLoad());
  ASSERT_EQ(loaded.words.index_state, built.map.words().index_state);
  const LocalizationRun restored =
      LocalizeSession(loaded.map, MapWords(loaded.words), *reader, options);
  EXPECT_TRUE(restored.index_restore.restored) << restored.index_restore.rebuild_reason;

  MapWords without = loaded.words;
  without.index_state.clear();
  const LocalizationRun rebuilt = LocalizeSession(loaded.map, std::move(without), *reader, options);
  EXPECT_FALSE(rebuilt.index_restore.restored);
  EXPECT_EQ(rebuilt.index_restore.rebuild_reason, "no stored index");
  ExpectSameRecords(restored, rebuilt, "restored vs rebuilt");
  EXPECT_GT(restored.summary.relocalization.num_relocalized, 0);

  // A damaged table: the index is rebuilt, the results are the same, and the
  // map file is not touched.
  {
    mapdb::SqliteDatabase db(path, /*read_only=*/false);
    db.Execute("UPDATE word_index SET state = zeroblob(length(state))");
  }
  const std::string damaged_bytes = FileBytes(path);
  MapAndWords damaged = LoadMapAndWords(path, options.LocalizationMapLoad());
  const LocalizationRun from_damaged =
      LocalizeSession(damaged.map, std::move(damaged.words), *reader, options);
  EXPECT_FALSE(from_damaged.index_restore.restored);
  EXPECT_NE(from_damaged.index_restore.rebuild_reason.find("fails its checksum"), std::string::npos)
      << from_damaged.index_restore.rebuild_reason;
  ExpectSameRecords(restored, from_damaged, "restored vs damaged");
  EXPECT_EQ(FileBytes(path), damaged_bytes) << "localization modified the map";
  EXPECT_NE(saved, damaged_bytes);
  std::filesystem::remove_all(dir);
}

TEST_F(EngineSessions, SessionsLocalizedOnOneLoadedMapDoNotDependOnTheOrder) {
  const std::string dir = testing::ProcessTempDir("engine_order");
  const std::string path = dir + "/map.db";
  SaveMap(MapOf("1+6", {"1", "6"}, false).map, path);
  const EngineOptions options = TestOptions();
  const MapAndWords loaded = LoadMapAndWords(path, options.LocalizationMapLoad());
  auto localize = [&](const std::string& session) {
    std::unique_ptr<SessionReader> reader = dataset_->OpenSession(session);
    return LocalizeSession(loaded.map, MapWords(loaded.words), *reader, options);
  };
  const LocalizationRun alone = localize("A");
  localize("F");
  const LocalizationRun after_f = localize("A");
  ExpectSameRecords(alone, after_f, "A alone vs A after F");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace duskmap
