// End-to-end: outputs are published without a race (issue 48). A file or
// folder that appears at an output while a command runs is never replaced
// without --overwrite, nor with it when it is not duskmap's; two commands
// writing one path: exactly one succeeds. And a report that a killed run or
// a full disk left half-written is recoverable: the next `report`,
// `run --resume` and `run --overwrite` replace it and clean the leftover
// staging folder, and a complete earlier report survives a failed one.
//
// The race is made deterministic through the program's test hook:
// DUSKMAP_TEST_BEFORE_PUBLISH runs a shell script right before each output
// takes its final name ($DUSKMAP_PUBLISH_PATH).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/map/map_store.h"
#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"
#include "tests/testing/temp_dir.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;
using duskmap::testing::ExpectOneLineError;
using duskmap::testing::ReadText;
using duskmap::testing::Snapshot;

// The error that ends what a command printed (after its progress lines).
void ExpectFinalError(const Result& r, const std::vector<std::string>& needles) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const size_t at = r.output.rfind("duskmap: error: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string line = r.output.substr(at);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << r.output;
  for (const std::string& needle : needles) {
    EXPECT_NE(line.find(needle), std::string::npos) << "missing '" << needle << "' in " << r.output;
  }
}

// Names in `folder` that a command's temporary files or folders have.
std::vector<std::string> Leftovers(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    for (const char* tag : {".partial-", ".saving", ".tmp-", ".old-"}) {
      if (name.find(tag) != std::string::npos) names.push_back(name);
    }
  }
  return names;
}

class PublishCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("publish_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(dir_.string(), 4, {"1", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
    const nlohmann::json experiment = {
        {"dataset", {{"path", Data()}, {"format", "synthetic"}}},
        {"features", {"OR"}},
        {"maps", {"1"}},
        {"localization_sessions", {"A"}}};
    std::ofstream(dir_ / "experiment.json") << experiment.dump(2);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string Data() { return (dir_ / "data").string(); }
  static std::string Map(const fs::path& output) {
    return "map --dataset " + Data() + " --sessions 1 --feature orb --output " + output.string();
  }
  static std::string Export(const fs::path& output) {
    return "features export --dataset " + Data() + " --type orb --sessions 1 --output " +
           output.string();
  }
  static std::string Run(const fs::path& output, const std::string& extra = "") {
    return "run " + (dir_ / "experiment.json").string() + " --output " + output.string() +
           " --jobs 2 --no-figures " + extra;
  }
  static std::string Report(const fs::path& results, const fs::path& output) {
    return "report " + (dir_ / "experiment.json").string() + " --results " + results.string() +
           " --output " + output.string() + " --no-figures";
  }
  // The prefix that runs `script` (sh) right before `path` is published.
  static std::string HookFor(const fs::path& path, const std::string& script) {
    const fs::path file = dir_ / ("hook_" + path.filename().string() + ".sh");
    std::ofstream(file) << "[ \"$DUSKMAP_PUBLISH_PATH\" = '" << path.string() << "' ] || exit 0\n"
                        << script << "\n";
    return "DUSKMAP_TEST_BEFORE_PUBLISH='sh " + file.string() + "' ";
  }
  // Runs two duskmap commands at once; their results.
  static std::pair<Result, Result> RunTogether(const std::string& a, const std::string& b) {
    const fs::path out_a = dir_ / "together_a.txt";
    const fs::path out_b = dir_ / "together_b.txt";
    const std::string exe = DUSKMAP_EXE;
    const std::string script = "(" + exe + " " + a + " > " + out_a.string() + " 2>&1; echo $? >> " +
                               out_a.string() + ".rc) & (" + exe + " " + b + " > " +
                               out_b.string() + " 2>&1; echo $? >> " + out_b.string() +
                               ".rc) & wait";
    fs::remove(out_a.string() + ".rc");
    fs::remove(out_b.string() + ".rc");
    EXPECT_EQ(std::system(script.c_str()), 0);
    return {{std::stoi(ReadText(out_a.string() + ".rc")), ReadText(out_a)},
            {std::stoi(ReadText(out_b.string() + ".rc")), ReadText(out_b)}};
  }
  // What a run killed as its report started, or cut short by a full disk,
  // left with the old code: a report/ with some of its files, and a staging
  // folder of a process that is gone.
  static void HalfWriteReport(const fs::path& results) {
    const fs::path report = results / "report";
    fs::remove_all(report);
    fs::create_directories(report / "tables");
    std::ofstream(report / "tables" / "single_session_maps.csv") << "feature,1\nOR,";
    std::ofstream(report / "tables.md.partial-4000000") << "| half";
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    const fs::path staging = results / ("report.tmp-" + std::to_string(child) + "-0");
    fs::create_directories(staging / "tables");
    std::ofstream(staging / "tables.md") << "| half";
  }
  static void ExpectCompleteReport(const fs::path& results) {
    for (const char* file : {"tables.md", "tables.tex", "cells.csv", "timeline.csv"}) {
      EXPECT_TRUE(fs::exists(results / "report" / file)) << file;
    }
    EXPECT_FALSE(fs::exists(results / "report" / "tables.md.partial-4000000"));
    EXPECT_TRUE(Leftovers(results).empty()) << Leftovers(results).front();
  }

  static fs::path dir_;
};

fs::path PublishCli::dir_;

TEST_F(PublishCli, MapNeverReplacesAFileThatAppearsWhileItRuns) {
  const fs::path target = dir_ / "race.db";
  const Result r = RunDuskmap(Map(target), HookFor(target, "echo notes > \"$DUSKMAP_PUBLISH_PATH\""));
  ExpectOneLineError(r, {target.string() + ": appeared while this command ran (--output); nothing "
                                           "was replaced (pass --overwrite to replace it)"});
  EXPECT_EQ(ReadText(target), "notes\n");
  // With --overwrite, a file that is not a map is still never replaced
  // (tested again when it appears after the check at the start).
  fs::remove(target);
  const Result o = RunDuskmap(Map(target) + " --overwrite",
                              HookFor(target, "echo other notes > \"$DUSKMAP_PUBLISH_PATH\""));
  ExpectOneLineError(o, {target.string() + ": not a duskmap map, so --overwrite will not replace it"});
  EXPECT_EQ(ReadText(target), "other notes\n");
  EXPECT_TRUE(Leftovers(dir_).empty()) << Leftovers(dir_).front();
}

// The other map is saved while this one is about to be: this one fails and
// the other's file is left byte for byte.
TEST_F(PublishCli, MapLosesTheRaceToAnotherMapIntoTheSamePath) {
  const fs::path target = dir_ / "twice.db";
  const std::string other = std::string(DUSKMAP_EXE) + " " + Map(target) + " > /dev/null && cp " +
                            target.string() + " " + target.string() + ".copy";
  const Result r = RunDuskmap(Map(target), HookFor(target, other));
  ExpectOneLineError(r, {target.string() + ": appeared while this command ran"});
  EXPECT_EQ(ReadText(target), ReadText(target.string() + ".copy"));
  EXPECT_TRUE(duskmap::IsDuskmapMapFile(target.string()));
}

TEST_F(PublishCli, TwoMapsAtOnceIntoOnePathExactlyOneSucceeds) {
  const fs::path target = dir_ / "concurrent.db";
  const auto [a, b] = RunTogether(Map(target), Map(target));
  EXPECT_EQ((a.exit_code == 0) + (b.exit_code == 0), 1) << a.output << "\n" << b.output;
  const Result& lost = a.exit_code == 0 ? b : a;
  ExpectOneLineError(lost, {target.string() + ": "});
  EXPECT_TRUE(duskmap::IsDuskmapMapFile(target.string()));
  EXPECT_TRUE(Leftovers(dir_).empty()) << Leftovers(dir_).front();
}

TEST_F(PublishCli, FeaturesExportNeverReplacesAFileThatAppears) {
  const fs::path target = dir_ / "race.h5";
  const Result r = RunDuskmap(Export(target), HookFor(target, "echo notes > \"$DUSKMAP_PUBLISH_PATH\""));
  ExpectFinalError(r, {target.string() + ": appeared while this command ran (--output)"});
  EXPECT_EQ(ReadText(target), "notes\n");
  fs::remove(target);
  const Result o = RunDuskmap(Export(target) + " --overwrite",
                              HookFor(target, "echo notes > \"$DUSKMAP_PUBLISH_PATH\""));
  ExpectFinalError(o, {target.string() + ": not a duskmap feature export"});
  EXPECT_EQ(ReadText(target), "notes\n");
  EXPECT_TRUE(Leftovers(dir_).empty()) << Leftovers(dir_).front();

  const fs::path both = dir_ / "concurrent.h5";
  const auto [a, b] = RunTogether(Export(both), Export(both));
  EXPECT_EQ((a.exit_code == 0) + (b.exit_code == 0), 1) << a.output << "\n" << b.output;
  ExpectFinalError(a.exit_code == 0 ? b : a, {both.string() + ": "});
  EXPECT_TRUE(Leftovers(dir_).empty()) << Leftovers(dir_).front();
}

TEST_F(PublishCli, GenerateNeverReplacesAFolderThatAppears) {
  nlohmann::json config = nlohmann::json::parse(std::ifstream(dir_ / "gen.json"));
  config["max_frames"] = 1;
  config["sessions"] = {config["sessions"][0]};
  std::ofstream(dir_ / "gen_one.json") << config.dump();
  const fs::path target = dir_ / "generated";
  const std::string generate = "generate --config " + (dir_ / "gen_one.json").string() + " --output " +
                               target.string();
  const Result r = RunDuskmap(generate, HookFor(target, "mkdir \"$DUSKMAP_PUBLISH_PATH\""));
  ExpectOneLineError(r, {target.string() + ": appeared while this command ran"});
  EXPECT_TRUE(fs::is_empty(target));  // an empty folder, which rename(2) alone would replace
  fs::remove(target);
  const Result o = RunDuskmap(generate + " --overwrite",
                              HookFor(target, "mkdir \"$DUSKMAP_PUBLISH_PATH\" && echo work > "
                                                  "\"$DUSKMAP_PUBLISH_PATH/thesis.tex\""));
  ExpectOneLineError(o, {target.string() + ": not a duskmap dataset", "left as it was"});
  EXPECT_EQ(ReadText(target / "thesis.tex"), "work\n");
  EXPECT_TRUE(Leftovers(dir_).empty()) << Leftovers(dir_).front();
}

// A half-written report/ and a stale staging folder: `report`,
// `run --resume` and `run --overwrite` each replace them with a whole report.
TEST_F(PublishCli, AHalfWrittenReportIsRecoverable) {
  const fs::path results = dir_ / "results";
  const Result first = RunDuskmap(Run(results));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string cells = ReadText(results / "report" / "cells.csv");
  const auto jobs = Snapshot(results / "jobs");

  HalfWriteReport(results);
  const Result report = RunDuskmap(Report(results, results / "report"));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  ExpectCompleteReport(results);
  EXPECT_EQ(ReadText(results / "report" / "cells.csv"), cells);

  HalfWriteReport(results);
  const Result resumed = RunDuskmap(Run(results, "--resume"));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  ExpectCompleteReport(results);
  EXPECT_EQ(ReadText(results / "report" / "cells.csv"), cells);
  EXPECT_EQ(Snapshot(results / "jobs"), jobs) << "a resume keeps every finished job";

  HalfWriteReport(results);
  const Result redone = RunDuskmap(Run(results, "--overwrite"));
  EXPECT_EQ(redone.exit_code, 0) << redone.output;
  ExpectCompleteReport(results);
  EXPECT_EQ(ReadText(results / "report" / "cells.csv"), cells);
}

// A report that fails part way (a full disk: here a 1-KiB file-size limit)
// leaves the complete earlier report byte for byte, and nothing beside it.
TEST_F(PublishCli, AFailedReportKeepsTheEarlierOne) {
  const fs::path results = dir_ / "results_full";
  const Result first = RunDuskmap(Run(results));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto before = Snapshot(results / "report");
  const Result full = RunDuskmap(Report(results, results / "report"), "trap '' XFSZ; ulimit -f 1; ");
  ExpectOneLineError(full, {(results / "report").string() + ": the report was not written",
                            "cannot write: File too large"});
  EXPECT_EQ(Snapshot(results / "report"), before);
  EXPECT_TRUE(Leftovers(results).empty()) << Leftovers(results).front();

  // A folder of the user's that appears at --output meanwhile is kept.
  const fs::path mine = dir_ / "my_report";
  const Result r = RunDuskmap(Report(results, mine),
                              HookFor(mine, "mkdir \"$DUSKMAP_PUBLISH_PATH\" && echo work > "
                                            "\"$DUSKMAP_PUBLISH_PATH/thesis.tex\""));
  ExpectOneLineError(r, {mine.string() + ": not an earlier report", "left as it was"});
  EXPECT_EQ(ReadText(mine / "thesis.tex"), "work\n");
  EXPECT_TRUE(Leftovers(dir_).empty()) << Leftovers(dir_).front();
}

}  // namespace
