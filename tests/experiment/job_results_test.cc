#include "slam/experiment/job_results.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "slam/experiment/job_results_json.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

// Summaries as duskmap run wrote them before the job summaries had codecs
// (out/quick of configs/quick_matrix.json; matched_session_per_frame cut to
// five frames).
const char kLocalizationSummary[] = R"({
 "has_ground_truth": true,
 "index_rebuild_reason": "",
 "index_restore_s": 0.003312763,
 "index_restored": true,
 "localizer_setup_s": 0.011861896,
 "map_from_cache": false,
 "map_load_s": 0.039942029,
 "matched_session_per_frame": [
  "3",
  "",
  "3",
  "3",
  ""
 ],
 "max_gap_m": 5.102757119766601,
 "mean_features": 481.35555555555555,
 "mean_inliers_pct": 20.87230990729299,
 "mean_jump_mm": 29.900438068838053,
 "mean_times_ms": {
  "features": 19.73115782222223,
  "loop_closure_detection": 3.242394099999999,
  "optimisation": 0.0,
  "proximity_detection": 0.04333703333333334,
  "total": 30.823076100000005,
  "transformation_estimation": 7.802482177777776
 },
 "median_lcd_te_ms": 10.818991,
 "memory_bytes": {
  "descriptors": 1947044,
  "filter": 51352,
  "graph": 105512,
  "keypoints_points": 562968,
  "words_index": 3036348
 },
 "num_frames": 90,
 "num_no_candidate": 0,
 "num_relocalized": 73,
 "num_within_55cm": 42,
 "num_within_55cm_bound": 81,
 "num_within_threshold": [
  72,
  73,
  73
 ],
 "num_wrong": 0
}
)";

const char kMapSummary[] = R"({
 "ate_mm": 80.63948368593047,
 "build_wall_s": 1.272965948,
 "descriptor_bytes_per_feature": 256,
 "index_build_s": 0.483197404,
 "links_per_type": {
  "loop_closure": 5,
  "odometry": 82,
  "proximity": 2
 },
 "mean_features": 484.48192771084337,
 "mean_times_ms": {
  "features": 19.307131493975902,
  "loop_closure_detection": 6.675227843373494,
  "optimisation": 0.33144955421686745,
  "proximity_detection": 0.017730927710843367,
  "total": 28.695987518072286,
  "transformation_estimation": 2.1167125662650603
 },
 "memory_bytes": {
  "descriptors": 2895264,
  "filter": 41288,
  "graph": 105512,
  "keypoints_points": 723816,
  "words_index": 5945240
 },
 "nodes_per_session": {
  "3": 83
 },
 "num_connected_components": 1,
 "num_nodes": 83,
 "vocabulary_words": 14023
}
)";

// An extract job's summary as duskmap run wrote it before it had a codec
// (the quick profile's extract/surf/A, with a feature cache kept across runs).
const char kExtractSummary[] = R"({
 "extraction_ms": {
  "max": 201.756902,
  "mean": 111.68217603333333,
  "median": 113.66301200000001
 },
 "extractor": "surf",
 "frames": 90,
 "mean_features": 598.3555555555556,
 "session": "A",
 "shared_cache": "stored f65ceea034aff113"
}
)";

// A job folder holding `json` as its summary.json.
fs::path JobWith(const nlohmann::json& json) {
  const fs::path dir = ::duskmap::testing::ProcessTempDir("job_results");
  WriteSummary(dir, json);
  return dir;
}

std::string SummaryText(const fs::path& job_dir) {
  std::ifstream in(job_dir / "summary.json");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(JobSummaryCodec, ReadsAndRewritesALocalizationSummaryByteForByte) {
  const fs::path dir = JobWith(nlohmann::json::parse(kLocalizationSummary));
  const LocalizationJobSummary s = ReadLocalizationJobSummary(dir);
  EXPECT_EQ(s.num_frames, 90);
  EXPECT_EQ(s.num_relocalized, 73);
  EXPECT_TRUE(s.has_ground_truth);
  EXPECT_EQ(s.num_within_threshold, (std::array<int, 3>{72, 73, 73}));
  EXPECT_EQ(s.num_within_55cm, 42);
  EXPECT_EQ(s.num_within_55cm_bound, 81);
  EXPECT_EQ(s.matched_session_per_frame, (std::vector<std::string>{"3", "", "3", "3", ""}));
  EXPECT_DOUBLE_EQ(s.mean_times_ms.transformation_estimation, 7.802482177777776);
  EXPECT_DOUBLE_EQ(s.median_lcd_te_ms, 10.818991);
  EXPECT_EQ(s.memory_bytes.at("words_index"), 3036348u);
  EXPECT_DOUBLE_EQ(s.map_load_s, 0.039942029);
  EXPECT_TRUE(s.index_restored);

  WriteSummary(dir, ToJsonObject(s));
  EXPECT_EQ(SummaryText(dir), kLocalizationSummary);
}

TEST(JobSummaryCodec, ReadsAndRewritesAMapSummaryByteForByte) {
  const fs::path dir = JobWith(nlohmann::json::parse(kMapSummary));
  const MapJobSummary s = ReadMapJobSummary(dir);
  EXPECT_EQ(s.num_nodes, 83);
  EXPECT_EQ(s.nodes_per_session.at("3"), 83);
  EXPECT_EQ(s.links_per_type.at("loop_closure"), 5);
  EXPECT_EQ(s.descriptor_bytes_per_feature, 256u);
  EXPECT_EQ(s.vocabulary_words, 14023);
  EXPECT_DOUBLE_EQ(s.ate_mm, 80.63948368593047);
  EXPECT_DOUBLE_EQ(s.index_build_s, 0.483197404);

  WriteSummary(dir, ToJsonObject(s));
  EXPECT_EQ(SummaryText(dir), kMapSummary);
}

TEST(JobSummaryCodec, OlderSummariesReadTheKeysAddedLaterAsDefaults) {
  nlohmann::json localization = nlohmann::json::parse(kLocalizationSummary);
  for (const char* key : {"map_load_s", "map_from_cache", "localizer_setup_s", "index_restore_s",
                          "index_restored", "index_rebuild_reason", "num_within_55cm_bound"}) {
    localization.erase(key);
  }
  const LocalizationJobSummary s = ReadLocalizationJobSummary(JobWith(localization));
  EXPECT_EQ(s.num_relocalized, 73);
  EXPECT_EQ(s.map_load_s, 0.0);
  EXPECT_FALSE(s.index_restored);
  EXPECT_EQ(s.index_rebuild_reason, "");
  EXPECT_EQ(s.num_within_55cm_bound, -1);  // not recorded

  nlohmann::json map = nlohmann::json::parse(kMapSummary);
  map.erase("index_build_s");
  const MapJobSummary m = ReadMapJobSummary(JobWith(map));
  EXPECT_EQ(m.num_nodes, 83);
  EXPECT_EQ(m.index_build_s, 0.0);
}

TEST(JobSummaryCodec, RefusesASummaryWithoutAKeyEverySummaryHolds) {
  nlohmann::json localization = nlohmann::json::parse(kLocalizationSummary);
  localization.erase("num_wrong");
  const fs::path dir = JobWith(localization);
  const std::string error = ::duskmap::testing::ErrorOf([&] { ReadLocalizationJobSummary(dir); });
  EXPECT_NE(error.find((dir / "summary.json").string() + ": missing key 'num_wrong'"),
            std::string::npos)
      << error;

  nlohmann::json map = nlohmann::json::parse(kMapSummary);
  map["mean_times_ms"].erase("total");
  const std::string nested = ::duskmap::testing::ErrorOf([&] { ReadMapJobSummary(JobWith(map)); });
  EXPECT_NE(nested.find("summary.json.mean_times_ms: missing key 'total'"), std::string::npos)
      << nested;
}

TEST(JobSummaryCodec, RefusesUnknownKeysAndWrongTypesNamingTheFile) {
  nlohmann::json localization = nlohmann::json::parse(kLocalizationSummary);
  localization["mean_times_ms"]["featurs"] = 1.0;
  const fs::path dir = JobWith(localization);
  const std::string unknown = ::duskmap::testing::ErrorOf([&] { ReadLocalizationJobSummary(dir); });
  EXPECT_NE(unknown.find((dir / "summary.json").string()), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("summary.json.mean_times_ms: unknown key 'featurs'"), std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("malformed job summary"), std::string::npos) << unknown;

  nlohmann::json map = nlohmann::json::parse(kMapSummary);
  map["num_nodes"] = "many";
  const std::string wrong = ::duskmap::testing::ErrorOf([&] { ReadMapJobSummary(JobWith(map)); });
  EXPECT_NE(wrong.find("summary.json.num_nodes: wrong type"), std::string::npos) << wrong;

  const std::string not_object =
      ::duskmap::testing::ErrorOf([&] { ReadMapJobSummary(JobWith(nlohmann::json::array())); });
  EXPECT_NE(not_object.find("expected an object, got array"), std::string::npos) << not_object;
}

TEST(JobSummaryCodec, ReadsAndRewritesAnExtractSummaryByteForByte) {
  const fs::path dir = JobWith(nlohmann::json::parse(kExtractSummary));
  const ExtractJobSummary s = ReadExtractJobSummary(dir);
  EXPECT_EQ(s.extractor, "surf");
  EXPECT_EQ(s.session, "A");
  EXPECT_EQ(s.frames, 90);
  EXPECT_DOUBLE_EQ(s.mean_features, 598.3555555555556);
  EXPECT_DOUBLE_EQ(s.extraction_ms.median, 113.66301200000001);
  EXPECT_DOUBLE_EQ(s.extraction_ms.mean, 111.68217603333333);
  EXPECT_DOUBLE_EQ(s.extraction_ms.max, 201.756902);
  EXPECT_EQ(s.shared_cache, "stored f65ceea034aff113");
  WriteSummary(dir, ToJsonObject(s));
  EXPECT_EQ(SummaryText(dir), kExtractSummary);

  // Without a feature cache kept across runs the key is left out, as before.
  nlohmann::json plain = nlohmann::json::parse(kExtractSummary);
  plain.erase("shared_cache");
  const fs::path plain_dir = JobWith(plain);
  const ExtractJobSummary p = ReadExtractJobSummary(plain_dir);
  EXPECT_EQ(p.shared_cache, "");
  EXPECT_EQ(ToJsonObject(p), plain);
}

TEST(JobSummaryCodec, RefusesACorruptOrOldExtractSummaryInOneLineNamingTheFile) {
  nlohmann::json old = nlohmann::json::parse(kExtractSummary);
  old["extraction_ms"].erase("mean");  // an extraction time without its mean
  const fs::path dir = JobWith(old);
  const std::string missing = ::duskmap::testing::ErrorOf([&] { ReadExtractJobSummary(dir); });
  EXPECT_EQ(missing, (dir / "summary.json").string() +
                         ".extraction_ms: missing key 'mean' (malformed job summary)");

  nlohmann::json renamed = nlohmann::json::parse(kExtractSummary);
  renamed["num_frames"] = renamed["frames"];
  renamed.erase("frames");
  const std::string unknown =
      ::duskmap::testing::ErrorOf([&] { ReadExtractJobSummary(JobWith(renamed)); });
  EXPECT_NE(unknown.find("summary.json"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("'num_frames'"), std::string::npos) << unknown;

  const fs::path cut = ::duskmap::testing::ProcessTempDir("job_results_cut");
  std::ofstream(cut / "summary.json") << std::string(kExtractSummary).substr(0, 60);
  const std::string truncated = ::duskmap::testing::ErrorOf([&] { ReadExtractJobSummary(cut); });
  EXPECT_EQ(truncated.rfind((cut / "summary.json").string(), 0), 0u) << truncated;
  EXPECT_EQ(truncated.find('\n'), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("malformed job summary"), std::string::npos) << truncated;
}

}  // namespace
}  // namespace duskmap
