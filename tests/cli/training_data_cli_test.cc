// End-to-end: `duskmap features training-data`'s bad input, each refused with
// one line naming the file and the problem before anything is rendered, and
// nothing at --out that duskmap did not write is replaced.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "slam/training/training_data_files.h"
#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"
#include "tests/testing/temp_dir.h"

namespace {
namespace fs = std::filesystem;

using duskmap::testing::ExpectOneLineError;
using duskmap::testing::ReadText;
using duskmap::testing::ProcessTempDir;
using duskmap::testing::RunDuskmap;

TEST(TrainingDataCli, MissingConfig) {
  const std::string dir = ProcessTempDir("training_cli");
  ExpectOneLineError(RunDuskmap("features training-data --config " + dir + "/absent.json --out " + dir + "/out"),
                     {"absent.json"});
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(TrainingDataCli, UnknownKeyInData) {
  const std::string dir = ProcessTempDir("training_cli");
  std::ofstream(dir + "/bad.json") << R"({"data": {"scenes": {"scenes": 2}, "max_pairs": 3}, "train": {}})";
  ExpectOneLineError(RunDuskmap("features training-data --config " + dir + "/bad.json --out " + dir + "/out"),
                     {"bad.json:data: unknown key 'max_pairs'"});
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(TrainingDataCli, UnknownTopLevelKey) {
  const std::string dir = ProcessTempDir("training_cli");
  std::ofstream(dir + "/top.json") << R"({"data": {}, "trian": {}})";
  ExpectOneLineError(RunDuskmap("features training-data --config " + dir + "/top.json --out " + dir + "/out"),
                     {"top.json: unknown key 'trian'"});
}

TEST(TrainingDataCli, RefusesToReplaceAFolderItDidNotWrite) {
  const std::string dir = ProcessTempDir("training_cli");
  std::ofstream(dir + "/ok.json") << R"({"data": {"scenes": {"scenes": 2}, "validation_scenes": 1}})";
  fs::create_directories(dir + "/mine");
  std::ofstream(dir + "/mine/notes.txt") << "keep";
  ExpectOneLineError(
      RunDuskmap("features training-data --config " + dir + "/ok.json --out " + dir + "/mine --overwrite"),
      {"mine", "not duskmap training data"});
  ExpectOneLineError(RunDuskmap("features training-data --config " + dir + "/ok.json --out " + dir + "/mine"),
                     {"mine", "--overwrite"});
  EXPECT_TRUE(fs::exists(dir + "/mine/notes.txt"));
  ExpectOneLineError(
      RunDuskmap("features training-data --config " + dir + "/ok.json --out " + dir + "/o --threads 0"),
      {"--threads must be >= 1"});
}

// Two tiny scenes (2 clock times x 3 frames): the same bytes on one thread
// and on two, a folder the reader accepts, one progress line per scene.
TEST(TrainingDataCli, OutputIsTheSameForAnyThreadCount) {
  const std::string dir = ProcessTempDir("training_cli");
  std::ofstream(dir + "/tiny.json")
      << R"({"data": {"scenes": {"scenes": 2, "hours_per_scene": 2, "frames_per_hour": 3}, "validation_scenes": 1}})";
  const auto one = RunDuskmap("features training-data --config " + dir + "/tiny.json --out " + dir + "/t1 --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_NE(one.output.find("scene 2/2 (validation): 6 frames"), std::string::npos) << one.output;
  const auto two = RunDuskmap("features training-data --config " + dir + "/tiny.json --out " + dir + "/t2 --threads 2");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  for (const char* file : {"manifest.json", "patches.u8", "points.f32"}) {
    EXPECT_EQ(ReadText(dir + "/t1/" + file), ReadText(dir + "/t2/" + file)) << file;
  }
  const duskmap::TrainingDataManifest manifest = duskmap::ReadTrainingDataManifest(dir + "/t2");
  EXPECT_GT(manifest.pairs, 0);
  EXPECT_EQ(manifest.scenes.size(), 2u);
}

}  // namespace
