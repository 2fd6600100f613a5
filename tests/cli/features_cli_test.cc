// End-to-end: `duskmap features export` and the h5 feature type. A built-in
// type exported and imported back gives the same maps and the same
// re-localization records as the type itself; an external extractor's file
// (scripts/external_sift_features.py) runs through map and localize.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/features/onnx_test_models.h"
#include "tests/features/static_scene.h"
#include "tests/features/two_plane_pair.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;
using duskmap::testing::ExpectOneLineError;
using duskmap::testing::ReadText;

std::vector<std::string> Lines(const std::string& path) {
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The records without their timings (the only field that differs run to run).
std::vector<nlohmann::json> RecordsWithoutTimings(const std::string& path) {
  std::vector<nlohmann::json> records;
  for (const std::string& line : Lines(path)) {
    nlohmann::json record = nlohmann::json::parse(line);
    record.erase("timings_ms");
    records.push_back(record);
  }
  return records;
}

class FeaturesCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("features_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(
        dir_, 8, {"1", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // An engine config whose features are imported from `h5`.
  static std::string H5Config(const std::string& name, const std::string& h5) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << nlohmann::json({{"features", {{"type", "h5"}, {"h5", {{"path", h5}}}}}}).dump();
    return path;
  }

  static std::string dir_;
};

std::string FeaturesCli::dir_;

TEST_F(FeaturesCli, ExportedSiftImportedBackGivesTheSameMapAndRecords) {
  const Result exported = RunDuskmap("features export --dataset " + dir_ + "/data --type sift --output " +
                                     dir_ + "/sift.h5 --image-list " + dir_ + "/images.tsv");
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_NE(exported.output.find("2 session(s), 16 frames"), std::string::npos) << exported.output;
  const std::vector<std::string> list = Lines(dir_ + "/images.tsv");
  ASSERT_EQ(list.size(), 16u);
  const size_t tab = list[0].find('\t');
  ASSERT_NE(tab, std::string::npos);
  EXPECT_EQ(list[0].substr(0, 6), "1/rgb/");
  EXPECT_TRUE(fs::exists(list[0].substr(tab + 1))) << list[0];
  EXPECT_EQ(list[8].substr(0, 6), "A/rgb/");

  const std::string h5 = H5Config("h5.json", dir_ + "/sift.h5");
  for (const auto& [name, flags] : {std::pair<std::string, std::string>{"builtin", "--feature sift"},
                                    {"imported", "--config " + h5}}) {
    const Result map = RunDuskmap("map --dataset " + dir_ + "/data --sessions 1 " + flags + " --output " +
                                  dir_ + "/" + name + ".db --summary " + dir_ + "/" + name + "_map.json");
    ASSERT_EQ(map.exit_code, 0) << map.output;
    const Result localize = RunDuskmap("localize --map " + dir_ + "/" + name + ".db --dataset " + dir_ +
                                       "/data --session A " + (name == "imported" ? "--config " + h5 : "") +
                                       " --records " + dir_ + "/" + name + ".jsonl");
    ASSERT_EQ(localize.exit_code, 0) << localize.output;
  }
  nlohmann::json builtin = nlohmann::json::parse(std::ifstream(dir_ + "/builtin_map.json"));
  nlohmann::json imported = nlohmann::json::parse(std::ifstream(dir_ + "/imported_map.json"));
  for (const char* key : {"nodes_per_session", "links_by_type", "vocabulary_words", "connected_session_groups"}) {
    ASSERT_TRUE(builtin.contains(key)) << key;
    EXPECT_EQ(builtin[key], imported[key]) << key;
  }
  for (const char* part : {"descriptors", "keypoints_points", "words_index", "graph"}) {
    EXPECT_EQ(builtin["memory_bytes"][part], imported["memory_bytes"][part]) << part;
  }
  const auto a = RecordsWithoutTimings(dir_ + "/builtin.jsonl");
  const auto b = RecordsWithoutTimings(dir_ + "/imported.jsonl");
  ASSERT_EQ(a.size(), 8u);
  EXPECT_EQ(a, b);
  // Without --config, localize makes its features as the map's were: the
  // map stores every feature option, the h5 file's path included.
  const Result stored = RunDuskmap("localize --map " + dir_ + "/imported.db --dataset " + dir_ +
                                   "/data --session A --records " + dir_ + "/imported_stored.jsonl");
  ASSERT_EQ(stored.exit_code, 0) << stored.output;
  EXPECT_EQ(RecordsWithoutTimings(dir_ + "/imported_stored.jsonl"), b);

  // An export is replaced only with --overwrite; other files never.
  const Result again = RunDuskmap("features export --dataset " + dir_ + "/data --type sift --sessions A --output " +
                                  dir_ + "/sift.h5");
  EXPECT_NE(again.exit_code, 0);
  const Result replaced = RunDuskmap("features export --dataset " + dir_ +
                                     "/data --type orb --sessions A --overwrite --output " + dir_ + "/sift.h5");
  EXPECT_EQ(replaced.exit_code, 0) << replaced.output;
  std::ofstream(dir_ + "/notes.h5") << "mine";
  const Result foreign = RunDuskmap("features export --dataset " + dir_ +
                                    "/data --type orb --overwrite --output " + dir_ + "/notes.h5");
  EXPECT_NE(foreign.exit_code, 0);
  EXPECT_EQ(Lines(dir_ + "/notes.h5"), std::vector<std::string>{"mine"});
}

TEST_F(FeaturesCli, BadExportsAndImportsFailWithOneLine) {
  const Result no_type = RunDuskmap("features export --dataset " + dir_ + "/data --output " + dir_ + "/x.h5");
  EXPECT_NE(no_type.exit_code, 0);
  EXPECT_NE(no_type.output.find("--output needs --type"), std::string::npos) << no_type.output;
  const Result nothing = RunDuskmap("features export --dataset " + dir_ + "/data --type orb");
  EXPECT_NE(nothing.exit_code, 0);
  EXPECT_NE(nothing.output.find("nothing to write"), std::string::npos) << nothing.output;
  EXPECT_FALSE(fs::exists(dir_ + "/x.h5"));

  // A file that lacks session A's images: the localization names file and group.
  ASSERT_EQ(RunDuskmap("features export --dataset " + dir_ + "/data --type orb --sessions 1 --output " + dir_ +
                       "/only1.h5").exit_code,
            0);
  const std::string config = H5Config("only1.json", dir_ + "/only1.h5");
  nlohmann::json binary = nlohmann::json::parse(std::ifstream(config));
  binary["features"]["h5"]["descriptor_kind"] = "binary";
  std::ofstream(config) << binary.dump();
  ASSERT_EQ(RunDuskmap("map --dataset " + dir_ + "/data --sessions 1 --config " + config + " --output " + dir_ +
                       "/only1.db").exit_code,
            0);
  const Result missing = RunDuskmap("localize --map " + dir_ + "/only1.db --dataset " + dir_ +
                                    "/data --session A --config " + config);
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find(dir_ + "/only1.h5: A/rgb/"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find(": no such image group"), std::string::npos) << missing.output;
}

// A column declared in an experiment config ({"code", "type": "h5", "path"})
// runs through `duskmap run` and its report like a built-in one: ORB exported
// and declared as "XO" gives ORB's cells.
TEST_F(FeaturesCli, DeclaredH5ColumnInAnExperimentEqualsTheBuiltInColumn) {
  ASSERT_EQ(RunDuskmap("features export --dataset " + dir_ + "/data --type orb --output " + dir_ +
                       "/orb.h5").exit_code,
            0);
  const nlohmann::json experiment = {
      {"dataset", {{"path", dir_ + "/data"}, {"format", "synthetic"}}},
      {"features", {"OR", {{"code", "XO"}, {"type", "h5"}, {"path", "orb.h5"}, {"descriptor_kind", "binary"}}}},
      {"maps", {"1"}},
      {"localization_sessions", {"A"}}};
  std::ofstream(dir_ + "/experiment.json") << experiment.dump(2);
  const Result run = RunDuskmap("run " + dir_ + "/experiment.json --output " + dir_ + "/results --jobs 2 --no-figures");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir_ + "/results/jobs/extract/h5-XO/A/summary.json"));
  std::map<std::string, std::string> cells;  // feature -> the row after "feature,"
  for (const std::string& line : Lines(dir_ + "/results/report/cells.csv")) {
    const size_t comma = line.find(',');
    std::string rest = line.substr(comma + 1);
    const std::string job = "localize/" + line.substr(0, comma) + "/";
    const size_t at = rest.find(job);
    if (at != std::string::npos) rest.replace(at, job.size(), "localize/*/");
    cells[line.substr(0, comma)] = rest;
  }
  ASSERT_TRUE(cells.count("OR") && cells.count("XO")) << run.output;
  EXPECT_EQ(cells["OR"], cells["XO"]);
  EXPECT_NE(Lines(dir_ + "/results/report/tables.md").size(), 0u);

  // A declared column that reuses a built-in code, or names no file, is refused.
  nlohmann::json clash = experiment;
  clash["features"][1]["code"] = "SI";
  std::ofstream(dir_ + "/clash.json") << clash.dump();
  const Result refused = RunDuskmap("run " + dir_ + "/clash.json --output " + dir_ + "/clash");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("declared code 'SI' is a built-in column's"), std::string::npos) << refused.output;
  nlohmann::json other = experiment;
  other["features"][1]["type"] = "sift";
  std::ofstream(dir_ + "/other.json") << other.dump();
  const Result type = RunDuskmap("run " + dir_ + "/other.json --output " + dir_ + "/other");
  EXPECT_NE(type.exit_code, 0);
  EXPECT_NE(type.output.find("'sift' cannot be declared"), std::string::npos) << type.output;
}

// The cells of one column of a run's report, each row after "<code>," with
// the job paths' code replaced by "*".
std::map<std::string, std::string> CellsByFeature(const std::string& cells_csv) {
  std::map<std::string, std::string> cells;
  for (const std::string& line : Lines(cells_csv)) {
    const size_t comma = line.find(',');
    std::string rest = line.substr(comma + 1);
    for (const std::string kind : {"localize/", "map/"}) {
      const std::string job = kind + line.substr(0, comma) + "/";
      for (size_t at = rest.find(job); at != std::string::npos; at = rest.find(job)) {
        rest.replace(at, job.size(), kind + "*/");
      }
    }
    cells[line.substr(0, comma)] += rest + "\n";
  }
  return cells;
}

// Columns declared as ONNX models ({"code", "type": "onnx", "model_path",
// contract keys}) run through `duskmap run`: SuperPoint's model declared with
// the onnx type's defaults (SuperPoint's contract) gives the SP column's
// cells; a sparse model runs as its own column; a model that breaks its
// declared contract is refused before any job runs.
TEST_F(FeaturesCli, DeclaredOnnxColumnsRunThroughTheMatrix) {
  const std::string superpoint = duskmap::testing::MakeSuperPointModel("superpoint_random.onnx");
  const std::string sparse = duskmap::testing::MakeOnnxFeatureModel("onnx_sparse.onnx", "--contract sparse");
  if (superpoint.empty() || sparse.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test models";
  std::ofstream(dir_ + "/sp_engine.json")
      << nlohmann::json({{"features", {{"superpoint", {{"model_path", superpoint}}}}}}).dump();
  const nlohmann::json experiment = {
      {"dataset", {{"path", dir_ + "/data"}, {"format", "synthetic"}}},
      {"features",
       {"SP", {{"code", "XS"}, {"type", "onnx"}, {"model_path", superpoint}},
        {{"code", "XP"}, {"type", "onnx"}, {"model_path", sparse}, {"contract", "sparse"},
         {"threshold", 0.52}}}},
      {"maps", {"1"}},
      {"localization_sessions", {"A"}},
      {"engine_config", dir_ + "/sp_engine.json"}};
  std::ofstream(dir_ + "/onnx_experiment.json") << experiment.dump(2);
  const Result run = RunDuskmap("run " + dir_ + "/onnx_experiment.json --output " + dir_ +
                                "/onnx_results --jobs 2 --no-figures");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir_ + "/onnx_results/jobs/extract/onnx-XS/A/summary.json"));
  EXPECT_TRUE(fs::exists(dir_ + "/onnx_results/jobs/extract/onnx-XP/A/summary.json"));
  std::map<std::string, std::string> cells = CellsByFeature(dir_ + "/onnx_results/report/cells.csv");
  ASSERT_TRUE(cells.count("SP") && cells.count("XS") && cells.count("XP")) << run.output;
  EXPECT_EQ(cells["SP"], cells["XS"]);
  EXPECT_NE(cells["XP"], cells["XS"]);

  // Read as a dense model, the sparse one has no score map: refused up front, naming it.
  nlohmann::json wrong = experiment;
  wrong["features"][2].erase("contract");
  std::ofstream(dir_ + "/onnx_wrong.json") << wrong.dump();
  const Result refused = RunDuskmap("run " + dir_ + "/onnx_wrong.json --output " + dir_ + "/onnx_wrong");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("onnx_sparse.onnx: the outputs do not match the declared dense contract"),
            std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir_ + "/onnx_wrong/jobs/extract"));
  nlohmann::json no_model = experiment;
  no_model["features"][2].erase("model_path");
  std::ofstream(dir_ + "/onnx_no_model.json") << no_model.dump();
  const Result missing = RunDuskmap("run " + dir_ + "/onnx_no_model.json --output " + dir_ + "/onnx_no_model");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("missing key 'model_path'"), std::string::npos) << missing.output;
}

// `features eval` on WxBS-style pairs (01.*, 02.*, corrs.txt): epipolar
// scoring, chosen automatically; --layout pairs on sequences is refused.
TEST_F(FeaturesCli, EvalScoresPairsByEpipolarGeometry) {
  duskmap::testing::TwoPlanePair().Write(dir_ + "/pairs/indoor/planes");
  const Result eval = RunDuskmap("features eval --data " + dir_ + "/pairs --types orb --out " + dir_ + "/pair_eval");
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_NE(eval.output.find("1 pair(s) with hand-clicked correspondences"), std::string::npos) << eval.output;
  const auto json = nlohmann::json::parse(std::ifstream(dir_ + "/pair_eval/features_eval.json"));
  EXPECT_EQ(json["layout"], "pairs");
  EXPECT_EQ(json["types"][0]["solved"], nlohmann::json({1, 1, 1}));
  EXPECT_EQ(json["types"][0]["categories"]["indoor"]["pairs"], 1);
  const Result wrong = RunDuskmap("features eval --layout pairs --data " + dir_ + "/data --types orb");
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.output.find("no pair folder"), std::string::npos) << wrong.output;
}

// A fixed camera's images without H files: the static layout, detected and
// said so, or forced; `SURF` is the surf type; the markdown has a row per
// pair. A sequence with some H files but not all is an error naming the
// missing one, never evaluated as static.
TEST(FeaturesEvalCli, StaticLayoutDetectedOrForced) {
  const std::string dir = duskmap::testing::ProcessTempDir("eval_static");
  duskmap::testing::WriteStaticScene(dir + "/cams/webcam", 3);
  const Result eval = RunDuskmap("features eval --data " + dir + "/cams --types SURF,orb --out " + dir + "/out");
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_NE(eval.output.find("1 sequence(s) in " + dir + "/cams, layout static (detected: no H1toNp file), 2 "
                             "pair(s), 2 type(s)"),
            std::string::npos)
      << eval.output;
  const auto json = nlohmann::json::parse(std::ifstream(dir + "/out/features_eval.json"));
  EXPECT_EQ(json["layout"], "static");
  EXPECT_EQ(json["types"][0]["type"], "surf");
  EXPECT_EQ(json["types"][0]["homography_accuracy"], 1.0);
  const std::string md = ReadText(dir + "/out/features_eval.md");
  EXPECT_NE(md.find("Layout: static (detected: no H1toNp file)"), std::string::npos) << md;
  for (const char* row : {"| surf | webcam | 1-2 |", "| surf | webcam | 1-3 |", "| orb | webcam | 1-3 |"}) {
    EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
  }

  // Forced on a folder whose H files are wrong: they are not used.
  for (const char* h : {"H1to2p", "H1to3p"}) std::ofstream(dir + "/cams/webcam/" + h) << "1 0 40\n0 1 0\n0 0 1\n";
  const Result forced = RunDuskmap("features eval --layout static --data " + dir + "/cams/webcam --types orb");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_NE(forced.output.find("layout static (--layout static; the H files of webcam are not used)"),
            std::string::npos)
      << forced.output;
  EXPECT_NE(forced.output.find("| orb | webcam | 1-3 |"), std::string::npos) << forced.output;
  const Result shifted = RunDuskmap("features eval --data " + dir + "/cams/webcam --types orb");
  ASSERT_EQ(shifted.exit_code, 0) << shifted.output;
  EXPECT_NE(shifted.output.find("layout homography (detected: H1toNp files)"), std::string::npos) << shifted.output;

  // Some H files but not all: the missing one is named.
  fs::remove(dir + "/cams/webcam/H1to3p");
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/cams --types orb"),
                     {dir + "/cams/webcam/H1to3p: missing (img3.png has no homography"});
  ExpectOneLineError(RunDuskmap("features eval --layout homography --data " + dir + "/cams --types orb"),
                     {dir + "/cams/webcam/H1to3p: missing"});
}

// --pairs and --pairs-file select pairs by image index; a selected pair that
// does not exist is named.
TEST(FeaturesEvalCli, PairsSelectASubset) {
  const std::string dir = duskmap::testing::ProcessTempDir("eval_pairs");
  duskmap::testing::WriteStaticScene(dir + "/webcam", 4);
  const Result eval = RunDuskmap("features eval --data " + dir + "/webcam --types orb --pairs 1-4,3-2 --out " +
                                 dir + "/out");
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_NE(eval.output.find("2 pair(s)"), std::string::npos) << eval.output;
  const auto json = nlohmann::json::parse(std::ifstream(dir + "/out/features_eval.json"));
  const nlohmann::json& detail = json["types"][0]["pairs_detail"];
  ASSERT_EQ(detail.size(), 2u);
  EXPECT_EQ(detail[0]["reference"], 1);
  EXPECT_EQ(detail[0]["target"], 4);
  EXPECT_EQ(detail[1]["reference"], 3);
  EXPECT_EQ(detail[1]["target"], 2);
  const std::string md = ReadText(dir + "/out/features_eval.md");
  EXPECT_NE(md.find("| orb | webcam | 3-2 |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| orb | webcam | 1-2 |"), std::string::npos) << md;

  std::ofstream(dir + "/night.txt") << "# the darkest\n1-4\nwebcam/1-3  # dusk\n";
  const Result listed = RunDuskmap("features eval --data " + dir + "/webcam --types orb --pairs-file " + dir +
                                   "/night.txt");
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_NE(listed.output.find("| orb | webcam | 1-3 |"), std::string::npos) << listed.output;
  EXPECT_EQ(listed.output.find("| orb | webcam | 1-2 |"), std::string::npos) << listed.output;

  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/webcam --types orb --pairs 1-2,1-9"),
                     {"--pairs: pair '1-9' does not exist in sequence webcam (no image 9; images 1, 2, 3, 4)"});
  std::ofstream(dir + "/bad.txt") << "1-2\n\n5-1\n";
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/webcam --types orb --pairs-file " + dir +
                                "/bad.txt"),
                     {dir + "/bad.txt:3: pair '5-1' does not exist in sequence webcam"});
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/webcam --types orb --pairs-file " + dir +
                                "/absent.txt"),
                     {dir + "/absent.txt: cannot read the pair list"});
}

// Type names in any case; --help lists the types and the default.
TEST(FeaturesEvalCli, TypesInAnyCaseAndListedInHelp) {
  const Result help = RunDuskmap("features eval --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  for (const char* needle : {"surf, sift, brief, brisk, kaze, daisy, orb, akaze, freak, dusknet, superpoint, onnx, h5",
                             "default: surf,sift,brief,brisk,kaze,daisy,orb,akaze,freak", "static",
                             "--pairs-file"}) {
    EXPECT_NE(help.output.find(needle), std::string::npos) << needle << "\n" << help.output;
  }
  const std::string dir = duskmap::testing::ProcessTempDir("eval_types");
  duskmap::testing::WriteStaticScene(dir + "/webcam", 2);
  const Result upper = RunDuskmap("features eval --data " + dir + "/webcam --types SURF,Brief");
  ASSERT_EQ(upper.exit_code, 0) << upper.output;
  EXPECT_NE(upper.output.find("| surf | webcam | 1-2 |"), std::string::npos) << upper.output;
  EXPECT_NE(upper.output.find("| brief | webcam | 1-2 |"), std::string::npos) << upper.output;
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/webcam --types SURFACE"),
                     {"--types: unknown feature type 'SURFACE' (known: surf, sift"});
}

// A WxBS-style pair folder missing an image: an error naming the file,
// whether the root or the folder itself is given.
TEST(FeaturesEvalCli, PairFolderMissingAnImageIsNamed) {
  const std::string dir = duskmap::testing::ProcessTempDir("eval_missing_pair");
  duskmap::testing::TwoPlanePair().Write(dir + "/pairs/day/street");
  duskmap::testing::TwoPlanePair().Write(dir + "/pairs/night/street");
  fs::remove(dir + "/pairs/night/street/02.png");
  const std::string missing = dir + "/pairs/night/street/02.{png,jpg,jpeg,ppm,bmp}: missing";
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/pairs --types orb"), {missing});
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/pairs/night/street --types orb"), {missing});
  const Result chosen = RunDuskmap("features eval --data " + dir + "/pairs/day --types orb --pairs day/street");
  ExpectOneLineError(chosen, {"--pairs: pair 'day/street' does not exist (pairs: street)"});
}

// --out onto a file: one line naming it, and the file is untouched.
TEST(FeaturesEvalCli, OutOntoAFileIsRefused) {
  const std::string dir = duskmap::testing::ProcessTempDir("eval_out_file");
  duskmap::testing::WriteStaticScene(dir + "/webcam", 2);
  std::ofstream(dir + "/notes.txt") << "mine\n";
  ExpectOneLineError(RunDuskmap("features eval --data " + dir + "/webcam --types orb --out " + dir + "/notes.txt"),
                     {"--out " + dir + "/notes.txt: exists and is not a folder"});
  EXPECT_EQ(ReadText(dir + "/notes.txt"), "mine\n");
  ExpectOneLineError(
      RunDuskmap("features eval --data " + dir + "/webcam --types orb --out " + dir + "/notes.txt/eval"),
      {"--out " + dir + "/notes.txt/eval: " + dir + "/notes.txt is not a folder"});
  EXPECT_EQ(ReadText(dir + "/notes.txt"), "mine\n");
  // A run that fails on its input leaves no --out folder behind.
  cv::imwrite(dir + "/webcam/img3.png", cv::Mat(100, 120, CV_8UC1, cv::Scalar(50)));
  const Result sizes = RunDuskmap("features eval --data " + dir + "/webcam --types orb --out " + dir + "/never");
  EXPECT_NE(sizes.exit_code, 0);
  EXPECT_NE(sizes.output.find(dir + "/webcam/img3.png: 120x100, but img1.png is 320x240"), std::string::npos)
      << sizes.output;
  EXPECT_FALSE(fs::exists(dir + "/never"));
}

// The worked example of docs/features.md: an external extractor (OpenCV's
// Python SIFT) reads the image list and writes the file the h5 type imports.
TEST_F(FeaturesCli, ExternalExtractorScriptRoundTrip) {
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  if (std::system((python + " -c 'import cv2, h5py, numpy' > /dev/null 2>&1").c_str()) != 0) {
    GTEST_SKIP() << "python3-opencv or python3-h5py is not installed (scripts/setup.sh installs them)";
  }
  ASSERT_EQ(RunDuskmap("features export --dataset " + dir_ + "/data --image-list " + dir_ + "/list.tsv").exit_code, 0);
  const std::string script = std::string(DUSKMAP_SOURCE_DIR) + "/scripts/external_sift_features.py";
  ASSERT_EQ(std::system((python + " " + script + " " + dir_ + "/list.tsv " + dir_ + "/external.h5 > /dev/null").c_str()), 0);
  const std::string config = H5Config("external.json", dir_ + "/external.h5");
  const Result map = RunDuskmap("map --dataset " + dir_ + "/data --sessions 1 --config " + config + " --output " +
                                dir_ + "/external.db --summary " + dir_ + "/external_map.json");
  ASSERT_EQ(map.exit_code, 0) << map.output;
  const Result localize = RunDuskmap("localize --map " + dir_ + "/external.db --dataset " + dir_ +
                                     "/data --session A --config " + config + " --summary " + dir_ +
                                     "/external_a.json");
  ASSERT_EQ(localize.exit_code, 0) << localize.output;
  const auto summary = nlohmann::json::parse(std::ifstream(dir_ + "/external_a.json"));
  EXPECT_EQ(summary["num_frames"], 8);
  EXPECT_GT(summary["num_relocalized"].get<int>(), 0) << summary.dump();
}

}  // namespace
