#include "slam/map/map_store.h"

#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/map/test_map.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

bool SamePose(const Rigid3d& a, const Rigid3d& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}

bool SameMatrix(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty()) return a.empty() && b.empty();
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

void ExpectNodesEqual(const MapNode& a, const MapNode& b) {
  EXPECT_EQ(a.session, b.session);
  EXPECT_EQ(a.frame_index, b.frame_index);
  EXPECT_EQ(a.timestamp_s, b.timestamp_s);
  EXPECT_TRUE(SamePose(a.map_from_body, b.map_from_body));
  EXPECT_TRUE(SamePose(a.odom_from_body, b.odom_from_body));
  EXPECT_TRUE(SamePose(a.body_from_camera, b.body_from_camera));
  EXPECT_EQ(a.camera.fx, b.camera.fx);
  EXPECT_EQ(a.camera.width, b.camera.width);
  ASSERT_EQ(a.truth_from_camera.has_value(), b.truth_from_camera.has_value());
  if (a.truth_from_camera) {
    EXPECT_TRUE(SamePose(*a.truth_from_camera, *b.truth_from_camera));
  }
  ASSERT_EQ(a.features.size(), b.features.size());
  EXPECT_EQ(a.features.storage(), b.features.storage());
  const FrameFeatures fa = a.features.Decode(), fb = b.features.Decode();
  for (size_t i = 0; i < fa.size(); ++i) {
    const cv::KeyPoint &ka = fa.keypoints[i], &kb = fb.keypoints[i];
    EXPECT_TRUE(ka.pt == kb.pt && ka.size == kb.size && ka.angle == kb.angle &&
                ka.response == kb.response && ka.octave == kb.octave && ka.class_id == kb.class_id);
    const Eigen::Vector3f &pa = fa.points_in_camera[i], &pb = fb.points_in_camera[i];
    EXPECT_TRUE(pa.allFinite() ? pa == pb : !pb.allFinite());
  }
  EXPECT_TRUE(SameMatrix(fa.descriptors, fb.descriptors));
  EXPECT_TRUE(SameMatrix(a.features.codes(), b.features.codes()));
  EXPECT_EQ(a.features.row_steps(), b.features.row_steps());
  EXPECT_EQ(fa.kind, fb.kind);
  EXPECT_EQ(a.word_ids, b.word_ids);
  EXPECT_EQ(a.word_counts, b.word_counts);
  EXPECT_EQ(a.vocabulary_features, b.vocabulary_features);
}

void ExpectMapsEqual(const Map& a, const Map& b) {
  EXPECT_EQ(a.metadata().feature_type, b.metadata().feature_type);
  EXPECT_EQ(a.metadata().feature_parameters_json, b.metadata().feature_parameters_json);
  EXPECT_EQ(a.metadata().engine_parameters_json, b.metadata().engine_parameters_json);
  EXPECT_EQ(a.metadata().descriptor_cv_type, b.metadata().descriptor_cv_type);
  EXPECT_EQ(a.metadata().descriptor_storage, b.metadata().descriptor_storage);
  EXPECT_EQ(a.last_node_id(), b.last_node_id());
  ASSERT_EQ(a.sessions().size(), b.sessions().size());
  for (size_t i = 0; i < a.sessions().size(); ++i) {
    EXPECT_EQ(a.sessions()[i].name, b.sessions()[i].name);
    EXPECT_EQ(a.sessions()[i].clock_time, b.sessions()[i].clock_time);
  }
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (const auto& [id, node] : a.nodes()) {
    ASSERT_TRUE(b.HasNode(id));
    ExpectNodesEqual(node, b.node(id));
  }
  ASSERT_EQ(a.links().size(), b.links().size());
  for (const auto& [key, link] : a.links()) {
    const Link& other = b.links().at(key);
    EXPECT_EQ(link.type, other.type);
    EXPECT_TRUE(SamePose(link.from_from_to, other.from_from_to));
    EXPECT_EQ(link.information, other.information);
  }
  EXPECT_EQ(a.words().ids, b.words().ids);
  EXPECT_TRUE(SameMatrix(a.words().descriptors, b.words().descriptors));
}

class MapStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::ProcessTempDir(std::string("map_store_") +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
    path_ = (dir_ / "map.db").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The temporary files of saves beside the map ("map.db.saving-<pid>-<n>").
  std::vector<std::string> Temporaries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("map.db.saving", 0) == 0) names.push_back(name);
    }
    return names;
  }

  // Runs an SQL statement on a saved map file (to forge bad inputs); the
  // table checksums then fail.
  void Tamper(const std::string& sql) { testing::ExecuteSql(path_, sql); }
  // The same, with the checksums recorded anew: the file as a writer with
  // those values would have saved it, for the checks behind the checksums.
  void TamperResealed(const std::string& sql) { testing::ExecuteSqlResealed(path_, sql); }

  // Expects LoadMap to throw InputError whose message contains `needle`.
  void ExpectLoadError(const std::string& needle, const MapLoadOptions& options = {}) {
    try {
      LoadMap(path_, options);
      FAIL() << "expected InputError containing '" << needle << "'";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(needle), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    }
  }

  fs::path dir_;
  std::string path_;
};

TEST_F(MapStoreTest, RoundTripFloatAndBinary) {
  for (bool binary : {false, true}) {
    const Map map = testing::MakeTestMap(6, 50, binary);
    SaveMap(map, path_);
    EXPECT_TRUE(Temporaries().empty());
    ExpectMapsEqual(map, LoadMap(path_));
  }
}

TEST_F(MapStoreTest, RoundTripKeepsIdsOfRemovedNodesReserved) {
  Map map = testing::MakeTestMap(3);
  map.RemoveNode(6);
  SaveMap(map, path_);
  const Map loaded = LoadMap(path_);
  EXPECT_EQ(loaded.NextNodeId(), 7);
  ExpectMapsEqual(map, loaded);
}

TEST_F(MapStoreTest, SaveOverwritesAndIgnoresStaleTemporary) {
  SaveMap(testing::MakeTestMap(2), path_);
  std::ofstream(path_ + ".saving") << "left over by an older version";
  const Map second = testing::MakeTestMap(4, 10, false, 99);
  SaveMap(second, path_);
  ExpectMapsEqual(second, LoadMap(path_));
  EXPECT_TRUE(Temporaries().empty());
}

// Without overwrite a save takes the name only while it is free: a file
// that appears at the path while the map is written (another save, the
// user's notes) is left as it was, and the save fails naming the path.
TEST_F(MapStoreTest, SaveWithoutOverwriteNeverReplacesAFileThatAppeared) {
  MapSaveOptions options;
  options.overwrite = false;
  options.flag = "--output";
  options.after_step = [&](MapSaveStep step) {
    if (step == MapSaveStep::kFlushed) std::ofstream(path_) << "notes";
  };
  try {
    SaveMap(testing::MakeTestMap(2), path_, options);
    FAIL() << "the save replaced a file that appeared";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path_ + ": appeared while this command ran (--output)"),
              std::string::npos)
        << e.what();
  }
  std::ifstream in(path_);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "notes");
  EXPECT_TRUE(Temporaries().empty());
  // With overwrite: a duskmap map is replaced, anything else never.
  options.overwrite = true;
  EXPECT_THROW(SaveMap(testing::MakeTestMap(2), path_, options), InputError);
  std::ifstream again(path_);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(again), {}), "notes");
  fs::remove(path_);
  options.after_step = nullptr;
  SaveMap(testing::MakeTestMap(2), path_, options);
  const Map second = testing::MakeTestMap(4, 10, false, 99);
  SaveMap(second, path_, options);
  ExpectMapsEqual(second, LoadMap(path_));
  EXPECT_TRUE(Temporaries().empty());
}

// A process killed (SIGKILL, as by the OOM killer or a user) right after
// each step of a save: before the rename the previous map loads unchanged,
// after it the new one loads complete, and the next save still succeeds.
// The kill comes from the save's own step hook, so no step is left to chance.
TEST_F(MapStoreTest, KillDuringSaveLeavesPreviousMapIntact) {
  const Map previous = testing::MakeTestMap(3);
  const Map next = testing::MakeTestMap(20, 200, false, 5);
  for (const MapSaveStep step : {MapSaveStep::kTemporaryCreated, MapSaveStep::kTablesWritten,
                                 MapSaveStep::kCommitted, MapSaveStep::kFlushed,
                                 MapSaveStep::kRenamed}) {
    SCOPED_TRACE(static_cast<int>(step));
    SaveMap(previous, path_);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      MapSaveOptions options;
      options.after_step = [step](MapSaveStep reached) {
        if (reached == step) ::raise(SIGKILL);
      };
      try {
        SaveMap(next, path_, options);
      } catch (...) {
        ::_exit(2);
      }
      ::_exit(0);  // not reached: the hook kills the process
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
    if (step == MapSaveStep::kRenamed) {
      EXPECT_TRUE(Temporaries().empty());
      ExpectMapsEqual(next, LoadMap(path_));
    } else {
      // Left behind, named with the killed pid; the next save removes it.
      const std::vector<std::string> left = Temporaries();
      ASSERT_EQ(left.size(), 1u);
      EXPECT_EQ(left[0].rfind("map.db.saving-" + std::to_string(child) + "-", 0), 0u) << left[0];
      ExpectMapsEqual(previous, LoadMap(path_));
    }
    SaveMap(next, path_);
    EXPECT_TRUE(Temporaries().empty());
    ExpectMapsEqual(next, LoadMap(path_));
  }
}

TEST_F(MapStoreTest, DifferentFeatureTypeIsRejected) {
  SaveMap(testing::MakeTestMap(2), path_);
  MapLoadOptions options;
  options.expected_feature_type = "sift";
  ExpectLoadError("built with feature type 'surf', expected 'sift'", options);
  options.expected_feature_type = "surf";
  EXPECT_NO_THROW(LoadMap(path_, options));
}

TEST_F(MapStoreTest, UnknownSchemaVersionIsRejected) {
  SaveMap(testing::MakeTestMap(2), path_);
  Tamper("UPDATE meta SET value = '7' WHERE key = 'schema_version'");
  ExpectLoadError("schema version 7 is not supported");
}

// A map written before 12-byte keypoints (schema 3), the stored vocabulary
// counts (schema 2) or compact node features (schema 1) gives a clear error.
TEST_F(MapStoreTest, OldSchemaVersionAsksForARebuild) {
  SaveMap(testing::MakeTestMap(2), path_);
  TamperResealed("UPDATE meta SET value = '4' WHERE key = 'schema_version'");
  ExpectLoadError("schema version 4 is not supported (this build reads 6; the map was written "
                  "by an older duskmap, rebuild it)");
  for (const char* version : {"3", "2", "1"}) {
    TamperResealed(std::string("UPDATE meta SET value = '") + version + "' WHERE key = 'schema_version'");
    ExpectLoadError(std::string("schema version ") + version + " is not supported (this build reads 6;");
  }
}

TEST_F(MapStoreTest, WordsLoadApart) {
  const Map map = testing::MakeTestMap(2);
  SaveMap(map, path_);
  MapLoadOptions apart;
  apart.load_words = false;
  const Map loaded = LoadMap(path_, apart);
  EXPECT_TRUE(loaded.words().ids.empty());
  EXPECT_EQ(loaded.words().next_word_id, map.words().next_word_id);
  const MapWords words = LoadMapWords(path_);
  EXPECT_EQ(words.ids, map.words().ids);
  EXPECT_TRUE(SameMatrix(words.descriptors, map.words().descriptors));
  Tamper("DELETE FROM words WHERE id = 4");
  ExpectLoadError("incomplete map", apart);
  EXPECT_THROW(LoadMapWords(path_), InputError);
}

TEST_F(MapStoreTest, MapAndWordsLoadTogetherAsApart) {
  const Map map = testing::MakeTestMap(2);
  SaveMap(map, path_);
  const MapAndWords loaded = LoadMapAndWords(path_);
  EXPECT_TRUE(loaded.map.words().ids.empty());
  EXPECT_EQ(loaded.map.words().next_word_id, map.words().next_word_id);
  EXPECT_EQ(loaded.map.nodes().size(), map.nodes().size());
  EXPECT_EQ(loaded.words.ids, map.words().ids);
  EXPECT_TRUE(SameMatrix(loaded.words.descriptors, map.words().descriptors));
  Tamper("DELETE FROM words WHERE id = 4");
  EXPECT_THROW(LoadMapAndWords(path_), InputError);
}

// A localizer that does not read keypoint responses loads without them;
// such a map cannot be saved (the file on disk stays as it was).
TEST_F(MapStoreTest, ResponsesCanBeLeftOutAndSuchAMapIsNotSaved) {
  const Map map = testing::MakeTestMap(2);
  SaveMap(map, path_);
  const std::vector<uint8_t> saved = ReadFileBytes(path_);
  MapLoadOptions options;
  options.keep_keypoint_responses = false;
  const Map loaded = LoadMap(path_, options);
  for (const auto& [id, node] : loaded.nodes()) {
    EXPECT_FALSE(node.features.has_responses());
    EXPECT_LT(node.features.KeypointPointMemoryBytes(),
              map.node(id).features.KeypointPointMemoryBytes());
    const FrameFeatures a = node.features.Decode(), b = map.node(id).features.Decode();
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a.keypoints[i].response, 0.0f);
      EXPECT_EQ(a.keypoints[i].pt, b.keypoints[i].pt);
    }
  }
  EXPECT_THROW(SaveMap(loaded, path_), InputError);
  EXPECT_EQ(ReadFileBytes(path_), saved);
}

TEST_F(MapStoreTest, VocabularyRoundTripsWithCountsAndNextWordId) {
  Map map = testing::MakeTestMap(2);
  MapWords words = map.words();
  words.next_word_id = 977;
  map.SetWords(words);
  SaveMap(map, path_);
  const Map loaded = LoadMap(path_);
  EXPECT_EQ(loaded.words().next_word_id, 977);
  EXPECT_EQ(loaded.words().ids, map.words().ids);
  TamperResealed("UPDATE nodes SET word_counts = x'01000000' WHERE id = 2");
  ExpectLoadError("node 2: 1 word counts for");
}

TEST_F(MapStoreTest, QuantizedDescriptorsRoundTrip) {
  const Map map = testing::MakeTestMap(3, 30, false, 11, DescriptorStorage::kUint8);
  SaveMap(map, path_);
  const Map loaded = LoadMap(path_);
  EXPECT_EQ(loaded.metadata().descriptor_storage, DescriptorStorage::kUint8);
  ExpectMapsEqual(map, loaded);
  TamperResealed("UPDATE nodes SET descriptor_scales = x'00000000' WHERE id = 2");
  ExpectLoadError("node 2: 1 descriptor scales, expected 60");
  SaveMap(map, path_);
  TamperResealed("UPDATE meta SET value = 'float64' WHERE key = 'descriptor_storage'");
  ExpectLoadError("unknown descriptor storage 'float64'");
  SaveMap(map, path_);
  TamperResealed("UPDATE meta SET value = 'int4' WHERE key = 'word_storage'");
  ExpectLoadError("unknown word storage 'int4'");
}

TEST_F(MapStoreTest, TruncatedFileIsRejected) {
  SaveMap(testing::MakeTestMap(20, 200), path_);
  const auto size = fs::file_size(path_);
  fs::resize_file(path_, size / 2);
  ExpectLoadError("truncated map file");
  fs::resize_file(path_, 50);
  ExpectLoadError("not an SQLite database, or truncated");
}

TEST_F(MapStoreTest, CorruptedFileIsRejected) {
  SaveMap(testing::MakeTestMap(20, 200), path_);
  {
    std::fstream file(path_, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(fs::file_size(path_) / 2));
    const std::string garbage(3000, '\x5a');
    file.write(garbage.data(), garbage.size());
  }
  try {
    LoadMap(path_);
    FAIL() << "a corrupted map loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path_), std::string::npos) << e.what();
  }
}

TEST_F(MapStoreTest, InconsistentRowsAreRejected) {
  SaveMap(testing::MakeTestMap(2), path_);
  TamperResealed("UPDATE nodes SET keypoints = x'0102' WHERE id = 2");
  ExpectLoadError("node 2 keypoints");
  SaveMap(testing::MakeTestMap(2), path_);
  TamperResealed("DELETE FROM links WHERE to_id = 2 AND from_id = 1");
  ExpectLoadError("row counts differ");
}

// Every table that carries results is checksummed: a changed value in any
// of them is an error naming the map and the table, whichever reader loads
// it (LoadMap, LoadMapWords, LoadMapAndWords).
TEST_F(MapStoreTest, ChangedValuesFailTheirTablesChecksum) {
  const Map map = testing::MakeTestMap(6, 50);
  const std::vector<std::pair<std::string, std::string>> changes = {
      {"meta", "UPDATE meta SET value = '9' WHERE key = 'descriptor_cols'"},
      {"sessions", "UPDATE sessions SET name = 'x' WHERE id = 0"},
      {"nodes", "UPDATE nodes SET timestamp_s = timestamp_s + 1e-9 WHERE id = 3"},
      {"nodes", "UPDATE nodes SET descriptors = zeroblob(length(descriptors)) WHERE id = 2"},
      {"links", "UPDATE links SET transform = (SELECT transform FROM links WHERE from_id = 2 LIMIT 1) WHERE from_id = 1"},
      {"words", "UPDATE words SET descriptor = zeroblob(length(descriptor)) WHERE id = 8"}};
  for (const auto& [table, sql] : changes) {
    SaveMap(map, path_);
    EXPECT_NO_THROW(LoadMap(path_));
    Tamper(sql);
    ExpectLoadError(path_ + ": table " + table + " fails its checksum");
    if (table == "words") {
      EXPECT_THROW(LoadMapWords(path_), InputError);
      EXPECT_THROW(LoadMapAndWords(path_), InputError);
    }
  }
  SaveMap(map, path_);
  Tamper("DROP TABLE checksums");
  ExpectLoadError("the map has no table checksums");
}

// Bits flipped anywhere in the file's pages (not the header): every load
// either fails with a one-line InputError naming the map, or gives the map
// that was saved.
TEST_F(MapStoreTest, FlippedBitsNeverLoadAsAnotherMap) {
  const Map map = testing::MakeTestMap(8, 80);
  SaveMap(map, path_);
  const std::vector<uint8_t> saved = ReadFileBytes(path_);
  std::mt19937 random(5);
  int failed = 0, same = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<uint8_t> bytes = saved;
    const int flips = 1 + trial % 10;
    for (int f = 0; f < flips; ++f) {
      const size_t at = 100 + random() % (bytes.size() - 100);
      bytes[at] ^= static_cast<uint8_t>(1u << (random() % 8));
    }
    std::ofstream(path_, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    try {
      const Map loaded = LoadMap(path_);
      ExpectMapsEqual(map, loaded);
      ++same;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path_), std::string::npos) << e.what();
      ++failed;
    }
  }
  EXPECT_GT(failed, 30);  // most flips land in data that is read
  EXPECT_EQ(failed + same, 60);
}

TEST_F(MapStoreTest, OnlyDuskmapMapsAreRecognisedAsSuch) {
  EXPECT_FALSE(IsDuskmapMapFile(path_));
  SaveMap(testing::MakeTestMap(2), path_);
  EXPECT_TRUE(IsDuskmapMapFile(path_));
  const std::string other = (dir_ / "notes.db").string();
  testing::ExecuteSql(other, "CREATE TABLE notes(x)");
  EXPECT_FALSE(IsDuskmapMapFile(other));
  std::ofstream((dir_ / "plain.txt").string()) << "text";
  EXPECT_FALSE(IsDuskmapMapFile((dir_ / "plain.txt").string()));
  EXPECT_FALSE(IsDuskmapMapFile(dir_.string()));
}

TEST_F(MapStoreTest, MissingOrForeignFileIsRejected) {
  ExpectLoadError("no such map file");
  std::ofstream(path_) << std::string(200, 'x');
  ExpectLoadError("not a duskmap map");
  fs::remove(path_);
  Tamper("CREATE TABLE other(x)");
  ExpectLoadError("not a duskmap map (no meta table)");
}

TEST_F(MapStoreTest, StoredIndexRoundTripsAndADamagedOneIsLeftOutWithTheReason) {
  Map map = testing::MakeTestMap(2);
  std::vector<uint8_t> state(5000);
  for (size_t i = 0; i < state.size(); ++i) state[i] = static_cast<uint8_t>(i * 7 + 3);
  map.SetWordIndexState(state);
  SaveMap(map, path_);
  MapAndWords loaded = LoadMapAndWords(path_);
  EXPECT_EQ(loaded.words.index_state, state);
  EXPECT_EQ(loaded.words.index_problem, "");
  EXPECT_EQ(LoadMap(path_).words().index_state, state);
  EXPECT_EQ(LoadMapWords(path_).index_state, state);

  // Other bytes of the same size: the map still loads, without the index,
  // and says why.
  Tamper("UPDATE word_index SET state = zeroblob(length(state))");
  MapAndWords damaged = LoadMapAndWords(path_);
  EXPECT_TRUE(damaged.words.index_state.empty());
  EXPECT_NE(damaged.words.index_problem.find("fails its checksum"), std::string::npos)
      << damaged.words.index_problem;
  EXPECT_NE(damaged.words.index_problem.find(path_), std::string::npos);
  EXPECT_EQ(damaged.words.ids, loaded.words.ids);

  SaveMap(map, path_);
  Tamper("UPDATE word_index SET version = 9");
  EXPECT_NE(LoadMapAndWords(path_).words.index_problem.find("version 9"), std::string::npos);
  SaveMap(map, path_);
  Tamper("DELETE FROM word_index");
  EXPECT_NE(LoadMapAndWords(path_).words.index_problem.find("empty"), std::string::npos);

  // A map saved without an index has no table and no problem.
  SaveMap(testing::MakeTestMap(2), path_);
  MapAndWords plain = LoadMapAndWords(path_);
  EXPECT_TRUE(plain.words.index_state.empty());
  EXPECT_EQ(plain.words.index_problem, "");
}

}  // namespace
}  // namespace duskmap
