#include "slam/experiment/shared_feature_cache.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "slam/core/file_checksum.h"
#include "slam/experiment/feature_cache.h"
#include "slam/experiment/feature_files.h"
#include "slam/features/embedded_model.h"
#include "slam/experiment/job_results_json.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

// A cache file of `frames` frames with 5 SURF-like features each.
void WriteCacheFile(const fs::path& path, int frames) {
  SessionInfo session;
  session.name = "1";
  FeatureCacheWriter writer(path, "surf", session);
  for (int i = 0; i < frames; ++i) {
    RgbdFrame frame;
    frame.frame_index = i;
    frame.camera = PinholeCamera{640, 480, 525.0, 525.0, 319.5, 239.5};
    FrameFeatures f;
    f.descriptors = cv::Mat(5, 64, CV_32F, cv::Scalar(0.1f * i));
    for (int k = 0; k < 5; ++k) {
      f.keypoints.emplace_back(10.f + k, 20.f, 7.f);
      f.points_in_camera.push_back(Eigen::Vector3f(0.1f * k, 0.2f, 1.5f));
    }
    writer.Append(frame, f);
  }
  writer.Close();
}

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

SharedFeatureCacheOptions Options(const std::string& dir) {
  SharedFeatureCacheOptions o;
  o.folder = dir + "/cache";
  o.program_id = "program-1";
  o.dataset_identity = {
      {"format", "synthetic"},
      {"sessions", {{{"name", "1"}, {"frames", 3}}, {{"name", "2"}, {"frames", 3}}}},
      {"content", {{"shared", "abc"}, {"sessions", {{"1", "111"}, {"2", "222"}}}}}};
  return o;
}

FeatureCacheInputs Inputs() {
  FeatureCacheInputs inputs;
  inputs.session = "1";
  inputs.cache_name = "surf";
  inputs.features.type = "surf";
  return inputs;
}

TEST(SharedFeatureCacheTest, EveryInputThatShapesFeaturesChangesTheKey) {
  const std::string dir = testing::ProcessTempDir("shared_cache_keys");
  const SharedFeatureCache cache(Options(dir));
  const std::string key = cache.KeyOf(Inputs());
  EXPECT_EQ(key.size(), 16u);
  EXPECT_EQ(cache.KeyOf(Inputs()), key);  // deterministic
  std::vector<FeatureCacheInputs> changed(6, Inputs());
  changed[0].session = "2";
  changed[1].cache_name = "onnx-XS";
  changed[2].features.surf.hessian_threshold = 200.0;
  changed[3].features.max_features = 500;
  changed[4].frame_step = 2;
  changed[5].max_frames_per_session = 10;
  for (const FeatureCacheInputs& inputs : changed) EXPECT_NE(cache.KeyOf(inputs), key);
  SharedFeatureCacheOptions other_program = Options(dir);
  other_program.program_id = "program-2";
  EXPECT_NE(SharedFeatureCache(other_program).KeyOf(Inputs()), key);
  // The session's own content checksum and the shared one are part of the
  // key; another session's are not (its change re-extracts only itself).
  SharedFeatureCacheOptions own_changed = Options(dir);
  own_changed.dataset_identity["content"]["sessions"]["1"] = "112";
  EXPECT_NE(SharedFeatureCache(own_changed).KeyOf(Inputs()), key);
  SharedFeatureCacheOptions shared_changed = Options(dir);
  shared_changed.dataset_identity["content"]["shared"] = "abd";
  EXPECT_NE(SharedFeatureCache(shared_changed).KeyOf(Inputs()), key);
  SharedFeatureCacheOptions other_changed = Options(dir);
  other_changed.dataset_identity["content"]["sessions"]["2"] = "223";
  other_changed.dataset_identity["sessions"][1]["frames"] = 4;
  EXPECT_EQ(SharedFeatureCache(other_changed).KeyOf(Inputs()), key);
  fs::remove_all(dir);
}

// Rewrites `path` with `bytes` and gives it back its earlier modification
// time: only the content says it changed.
void RewriteKeepingTime(const fs::path& path, const std::string& bytes) {
  const fs::file_time_type time = fs::last_write_time(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  fs::last_write_time(path, time);
}

// An ONNX model or an h5 file rewritten in place with the same size and time
// is another key (not reused); unchanged, the key stays (reused). An h5
// folder's per-session files key their own session only. A checksum the run
// computed once is used as given.
TEST(SharedFeatureCacheTest, ModelAndH5FilesKeyByContent) {
  const std::string dir = testing::ProcessTempDir("shared_cache_files");
  const SharedFeatureCache cache(Options(dir));
  FeatureCacheInputs onnx = Inputs();
  onnx.features.type = "onnx";
  onnx.features.onnx.model_path = dir + "/model.onnx";
  std::ofstream(onnx.features.onnx.model_path) << "model one";
  const std::string before = cache.KeyOf(onnx);
  EXPECT_EQ(cache.KeyOf(onnx), before);
  RewriteKeepingTime(onnx.features.onnx.model_path, "model two");
  EXPECT_NE(cache.KeyOf(onnx), before);
  RewriteKeepingTime(onnx.features.onnx.model_path, "model one");
  EXPECT_EQ(cache.KeyOf(onnx), before) << "the same bytes again: the entry serves again";
  SharedFeatureCacheOptions given = Options(dir);
  given.file_checksums = {{onnx.features.onnx.model_path, "0123456789abcdef"}};
  EXPECT_NE(SharedFeatureCache(given).KeyOf(onnx), before);

  FeatureCacheInputs h5 = Inputs();
  h5.features.type = "h5";
  h5.features.h5.path = dir + "/features.h5";
  std::ofstream(h5.features.h5.path) << "h5 bytes A";
  const std::string h5_before = cache.KeyOf(h5);
  RewriteKeepingTime(h5.features.h5.path, "h5 bytes B");
  EXPECT_NE(cache.KeyOf(h5), h5_before);

  FeatureCacheInputs folder = Inputs();  // session "1"
  folder.features.type = "h5";
  folder.features.h5.path = dir + "/per_session";
  fs::create_directories(folder.features.h5.path);
  std::ofstream(folder.features.h5.path + "/1.h5") << "session one";
  std::ofstream(folder.features.h5.path + "/2.h5") << "session two";
  const std::string folder_before = cache.KeyOf(folder);
  RewriteKeepingTime(folder.features.h5.path + "/2.h5", "session 2!!");
  EXPECT_EQ(cache.KeyOf(folder), folder_before);
  RewriteKeepingTime(folder.features.h5.path + "/1.h5", "session 1!!");
  EXPECT_NE(cache.KeyOf(folder), folder_before);
  fs::remove_all(dir);
}

// dusknet keys on its model's content: the embedded model's checksum (that
// of slam/features/models/dusknet.onnx as built) without model_path, the
// named file's with it.
TEST(SharedFeatureCacheTest, DuskNetKeysByTheEmbeddedModelOrItsFile) {
  const std::string dir = testing::ProcessTempDir("shared_cache_dusknet");
  const SharedFeatureCache cache(Options(dir));
  FeatureCacheInputs embedded = Inputs();
  embedded.cache_name = embedded.features.type = "dusknet";
  const EmbeddedModel& model = EmbeddedDuskNetModel();
  EXPECT_TRUE(FeatureFilesOf(embedded.features).empty());
  EXPECT_EQ(EmbeddedModelChecksums(embedded.features),
            nlohmann::json({{"embedded:dusknet.onnx", model.checksum_hex}}));
  EXPECT_EQ(model.checksum_hex,
            FileChecksum64Hex(std::string(DUSKMAP_SOURCE_DIR) + "/slam/features/models/dusknet.onnx"))
      << "the embedded model is not the committed one";
  const std::string embedded_key = cache.KeyOf(embedded);
  EXPECT_EQ(cache.KeyOf(embedded), embedded_key);

  FeatureCacheInputs file = embedded;
  file.features.dusknet.model_path = dir + "/candidate.onnx";
  std::ofstream(file.features.dusknet.model_path) << "candidate one";
  EXPECT_EQ(FeatureFilesOf(file.features), std::vector<std::string>{file.features.dusknet.model_path});
  EXPECT_TRUE(EmbeddedModelChecksums(file.features).empty());
  const std::string file_key = cache.KeyOf(file);
  EXPECT_NE(file_key, embedded_key);
  RewriteKeepingTime(file.features.dusknet.model_path, "candidate two");
  EXPECT_NE(cache.KeyOf(file), file_key);

  // Other types run no embedded model.
  EXPECT_TRUE(EmbeddedModelChecksums(Inputs().features).empty());
  fs::remove_all(dir);
}

TEST(SharedFeatureCacheTest, StoredEntriesRestoreAndDamagedOnesAreMisses) {
  const std::string dir = testing::ProcessTempDir("shared_cache_entries");
  const SharedFeatureCache cache(Options(dir));
  ASSERT_TRUE(cache.enabled());
  const std::string key = cache.KeyOf(Inputs());
  EXPECT_FALSE(cache.Restore(key, dir + "/restored.bin").has_value());  // empty cache

  WriteCacheFile(dir + "/extracted.bin", 3);
  ExtractJobSummary summary;
  summary.extractor = "surf";
  summary.session = "1";
  summary.frames = 3;
  summary.mean_features = 5.0;
  summary.extraction_ms = {12.0, 12.5, 14.0};
  cache.Store(key, dir + "/extracted.bin", summary);
  const std::optional<ExtractJobSummary> restored = cache.Restore(key, dir + "/restored.bin");
  ASSERT_TRUE(restored.has_value());
  EXPECT_EQ(ToJsonObject(*restored), ToJsonObject(summary));
  EXPECT_EQ(Bytes(dir + "/restored.bin"), Bytes(dir + "/extracted.bin"));

  // A job that extracts again writes a fresh file: the entry it was linked
  // from stays whole.
  WriteCacheFile(dir + "/restored.bin", 1);
  ASSERT_TRUE(cache.Restore(key, dir + "/again.bin").has_value());
  EXPECT_EQ(Bytes(dir + "/again.bin"), Bytes(dir + "/extracted.bin"));

  // A summary whose frame count disagrees with the file, or a cut file: a
  // miss, and the entry is gone.
  const fs::path entry = fs::path(dir) / "cache" / key;
  nlohmann::json four = ToJsonObject(summary);
  four["frames"] = 4;
  std::ofstream(entry / SharedFeatureCache::kSummaryFile) << four.dump();
  EXPECT_FALSE(cache.Restore(key, dir + "/x.bin").has_value());
  EXPECT_FALSE(fs::exists(entry));
  // A summary that is no extract job's (an older entry's, a key missing): a miss.
  cache.Store(key, dir + "/extracted.bin", summary);
  std::ofstream(entry / SharedFeatureCache::kSummaryFile) << nlohmann::json({{"frames", 3}}).dump();
  EXPECT_FALSE(cache.Restore(key, dir + "/x.bin").has_value());
  EXPECT_FALSE(fs::exists(entry));
  cache.Store(key, dir + "/extracted.bin", summary);
  fs::resize_file(entry / SharedFeatureCache::kEntryFile, fs::file_size(entry / SharedFeatureCache::kEntryFile) / 2);
  EXPECT_FALSE(cache.Restore(key, dir + "/x.bin").has_value());
  EXPECT_FALSE(fs::exists(entry));

  // Without a folder the cache does nothing.
  const SharedFeatureCache none{SharedFeatureCacheOptions{}};
  EXPECT_FALSE(none.enabled());
  none.Store(key, dir + "/extracted.bin", summary);
  EXPECT_FALSE(none.Restore(key, dir + "/x.bin").has_value());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace duskmap
