// End-to-end: inputs that are not what a command expects get a one-line
// error naming the file (or flag) and the problem, and a non-zero exit
// (issue 48): FIFOs and folders where a file is expected (a FIFO given as
// --map blocked forever), options beyond a sane range, an image header
// declaring 100000x100000 pixels in `features eval`, unreadable --textures.
// Each command runs under `timeout`: a command that blocks again fails.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/features/two_plane_pair.h"
#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"
#include "tests/testing/temp_dir.h"

namespace {

namespace fs = std::filesystem;

using duskmap::testing::CliResult;
using duskmap::testing::ExpectOneLineError;

CliResult RunTimed(const std::string& args) { return duskmap::testing::RunDuskmap(args, "timeout 120 "); }

std::string Fifo(const fs::path& dir, const std::string& name) {
  const std::string path = (dir / name).string();
  EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0) << path;
  return path;
}

TEST(InputCli, FifosAndFoldersGivenAsFilesAreRefusedWithoutBlocking) {
  const fs::path dir = duskmap::testing::ProcessTempDir("input_cli_fifo");
  const std::string map = Fifo(dir, "map.db");
  ExpectOneLineError(RunTimed("localize --map " + map + " --dataset " + dir.string() + " --session A"),
                     {map + ": is a FIFO (named pipe), not a regular file"});
  const std::string config = Fifo(dir, "engine.json");
  ExpectOneLineError(RunTimed("map --dataset " + (dir / "dataset").string() + " --sessions 1 --config " + config +
                              " --output " + (dir / "m.db").string()),
                     {config + ": is a FIFO (named pipe), not a regular file"});
  const std::string experiment = Fifo(dir, "experiment.json");
  ExpectOneLineError(RunTimed("run " + experiment + " --output " + (dir / "results").string()),
                     {experiment + ": is a FIFO (named pipe), not a regular file"});
  const std::string rates = Fifo(dir, "cells.csv");
  ExpectOneLineError(RunTimed("check-rates --baseline " + rates + " --current " + rates),
                     {rates + ": is a FIFO (named pipe), not a regular file"});
  // A results folder's run.json (report), features eval's --pairs-file and a pair's corrs.txt.
  fs::create_directories(dir / "results");
  const std::string manifest = Fifo(dir / "results", "run.json");
  std::ofstream(dir / "experiment_ok.json")
      << R"({"dataset": {"path": "/nonexistent/data", "format": "synthetic"}, "features": ["OR"],)"
      << R"( "maps": ["1"], "localization_sessions": ["A"]})";
  ExpectOneLineError(RunTimed("report " + (dir / "experiment_ok.json").string() + " --results " +
                              (dir / "results").string() + " --output " + (dir / "report").string()),
                     {manifest + ": is a FIFO (named pipe), not a regular file"});
  const fs::path pair = dir / "pairs" / "indoor" / "planes";
  duskmap::testing::TwoPlanePair().Write(pair);
  const std::string pair_list = Fifo(dir, "pairs.txt");
  ExpectOneLineError(RunTimed("features eval --data " + (dir / "pairs").string() + " --types orb --pairs-file " +
                              pair_list),
                     {"--pairs-file " + pair_list + ": is a FIFO (named pipe), not a regular file"});
  fs::remove(pair / "corrs.txt");
  const std::string corrs = Fifo(pair, "corrs.txt");
  const CliResult eval = RunTimed("features eval --data " + (dir / "pairs").string() + " --types orb");
  EXPECT_EQ(eval.exit_code, 1) << eval.output;
  EXPECT_NE(eval.output.find("duskmap: error: " + corrs + ": is a FIFO (named pipe), not a regular file\n"),
            std::string::npos)
      << eval.output;
  const fs::path folder = dir / "generator.json";
  fs::create_directories(folder);
  ExpectOneLineError(RunTimed("generate --config " + folder.string() + " --output " + (dir / "data").string()),
                     {folder.string() + ": is a folder, not a regular file"});
  EXPECT_FALSE(fs::exists(dir / "data"));
}

TEST(InputCli, DatasetStatsRefusesOptionsBeyondASaneRange) {
  const fs::path dir = duskmap::testing::ProcessTempDir("input_cli_stats");
  // Checked before the dataset is opened (there is none here).
  ExpectOneLineError(RunTimed("dataset-stats --dataset " + dir.string() + " --max-features 1000000000"),
                     {"--max-features", "must be in [10, 100000], got 1000000000"});
  // "1e9" is no integer to the option parser: refused before it reaches the options.
  const CliResult exponent = RunTimed("dataset-stats --dataset " + dir.string() + " --max-features 1e9");
  EXPECT_NE(exponent.exit_code, 0) << exponent.output;
  EXPECT_NE(exponent.output.find("--max-features"), std::string::npos) << exponent.output;
  ExpectOneLineError(RunTimed("dataset-stats --dataset " + dir.string() + " --max-error-px 1e308"),
                     {"--max-error-px", "must be in (0, 100], got 1e+308"});
}

// A PPM header declaring 100000x100000 pixels failed an OpenCV assertion.
TEST(InputCli, FeaturesEvalRefusesAnImageOverThePixelLimitBeforeDecoding) {
  const fs::path dir = duskmap::testing::ProcessTempDir("input_cli_eval");
  const fs::path pair = dir / "pairs" / "indoor" / "planes";
  duskmap::testing::TwoPlanePair().Write(pair);
  fs::remove(pair / "01.png");
  std::ofstream(pair / "01.ppm", std::ios::binary) << "P6\n100000 100000\n255\n" << std::string(64, '\0');
  const CliResult eval = RunTimed("features eval --data " + (dir / "pairs").string() + " --types orb --out " +
                                  (dir / "eval").string());
  EXPECT_EQ(eval.exit_code, 1) << eval.output;
  // After the line that says what it found, one error line.
  const std::string error = "duskmap: error: " + (pair / "01.ppm").string() +
                            ": 100000x100000 image exceeds the 64-Mpixel limit\n";
  ASSERT_GE(eval.output.size(), error.size()) << eval.output;
  EXPECT_EQ(eval.output.substr(eval.output.size() - error.size()), error) << eval.output;
  EXPECT_EQ(std::count(eval.output.begin(), eval.output.end(), '\n'), 2) << eval.output;
}

// An image of the --textures folder that cannot be used stops `generate`,
// naming it, before any session is rendered.
TEST(InputCli, GenerateRefusesATexturesImageItCannotRead) {
  const fs::path dir = duskmap::testing::ProcessTempDir("input_cli_textures");
  const fs::path textures = dir / "textures";
  fs::create_directories(textures);
  std::ofstream(textures / "poster.png", std::ios::binary) << "\x89PNG\r\n\x1a\n" << std::string(40, 'x');
  nlohmann::json config = nlohmann::json::parse(
      std::ifstream(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment_boxes.json"));
  config["max_frames"] = 2;
  std::ofstream(dir / "gen.json") << config.dump();
  ExpectOneLineError(RunTimed("generate --config " + (dir / "gen.json").string() + " --output " +
                         (dir / "data").string() + " --textures " + textures.string()),
                     {(textures / "poster.png").string() + ": PNG is truncated (no IEND chunk)"});
}

}  // namespace
