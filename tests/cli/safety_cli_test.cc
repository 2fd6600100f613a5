// End-to-end: what duskmap must never do to the user's files, and what it
// must refuse (issue 21). Every case asserts the exit code, that the one-line
// message names the file and the problem, and that every file that existed
// before is byte-identical afterwards.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/io/output_safety.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;
using duskmap::testing::ExpectOneLineError;
using duskmap::testing::ReadText;
using duskmap::testing::Snapshot;

class SafetyCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("safety_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(
        dir_.string(), 6, {"1", "2", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
    WriteExperiment("experiment.json", Experiment());
    const Result map = RunDuskmap("map --dataset " + Data() + " --sessions 1 --feature orb --output " +
                                  (dir_ / "m.db").string());
    ASSERT_EQ(map.exit_code, 0) << map.output;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string Data() { return (dir_ / "data").string(); }
  static nlohmann::json Experiment() {
    return {{"dataset", {{"path", Data()}, {"format", "synthetic"}}},
            {"features", {"OR"}},
            {"maps", {"1", "1+2"}},
            {"localization_sessions", {"A"}}};
  }
  static std::string WriteExperiment(const std::string& name, const nlohmann::json& experiment) {
    std::ofstream(dir_ / name) << experiment.dump(2);
    return (dir_ / name).string();
  }
  static std::string Run(const std::string& config, const std::string& output,
                         const std::string& extra = "") {
    return "run " + config + " --output " + (dir_ / output).string() + " --jobs 2 --no-figures " +
           extra;
  }
  // A folder of the user's own files.
  static fs::path UserFolder(const std::string& name) {
    const fs::path folder = dir_ / name;
    fs::create_directories(folder / "sub");
    std::ofstream(folder / "thesis.tex") << "years of work";
    std::ofstream(folder / "sub" / "data.csv") << "1,2,3";
    return folder;
  }

  static fs::path dir_;
};

fs::path SafetyCli::dir_;

TEST_F(SafetyCli, GenerateOverwriteReplacesOnlyADataset) {
  const fs::path mine = UserFolder("mine");
  const auto before = Snapshot(mine);
  const std::string generate = "generate --config " + (dir_ / "gen.json").string() + " --overwrite --output ";
  ExpectOneLineError(RunDuskmap(generate + mine.string()),
                     {mine.string() + ": not a duskmap dataset", "will not replace it"});
  EXPECT_EQ(Snapshot(mine), before);

  // A results folder of `duskmap run` is not a dataset either; nor a file.
  const fs::path results = dir_ / "results_like";
  fs::create_directories(results);
  std::ofstream(results / "run.json") << "{}";
  ExpectOneLineError(RunDuskmap(generate + results.string()), {"not a duskmap dataset"});
  EXPECT_TRUE(fs::exists(results / "run.json"));
  const fs::path file = dir_ / "notes.txt";
  std::ofstream(file) << "notes";
  ExpectOneLineError(RunDuskmap(generate + file.string()), {file.string(), "not a duskmap dataset"});
  EXPECT_EQ(ReadText(file), "notes");

  // `--output .` from inside a dataset: the current folder is never replaced.
  const auto data_before = Snapshot(dir_ / "data");
  ExpectOneLineError(RunDuskmap(generate + ".", "cd " + Data() + " && "),
                     {"is the current folder or one of its parents"});
  EXPECT_EQ(Snapshot(dir_ / "data"), data_before);

  // Nothing else is left beside them (no staging or old folders).
  for (const auto& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
    EXPECT_EQ(name.find(".old-"), std::string::npos) << name;
  }
}

TEST_F(SafetyCli, GenerateRefusesBadThreadsAndFocalLengths) {
  const std::string generate = "generate --config " + (dir_ / "gen.json").string() + " --output " +
                               (dir_ / "never").string();
  ExpectOneLineError(RunDuskmap(generate + " --threads 0"), {"--threads: must be >= 1, got 0"});
  ExpectOneLineError(RunDuskmap(generate + " --threads -1"), {"--threads: must be >= 1, got -1"});
  nlohmann::json config = nlohmann::json::parse(std::ifstream(dir_ / "gen.json"));
  config["camera"]["fx"] = 1e308;
  std::ofstream(dir_ / "gen_fx.json") << config.dump();
  ExpectOneLineError(RunDuskmap("generate --config " + (dir_ / "gen_fx.json").string() +
                                " --output " + (dir_ / "never").string()),
                     {(dir_ / "gen_fx.json").string(), "camera.fx"});
  EXPECT_FALSE(fs::exists(dir_ / "never"));
}

TEST_F(SafetyCli, OutputsNeverReplaceInputs) {
  const fs::path map = dir_ / "m.db";
  const auto map_before = Snapshot(map);
  const auto data_before = Snapshot(dir_ / "data");
  ExpectOneLineError(RunDuskmap("localize --map " + map.string() + " --dataset " + Data() +
                                " --session A --trajectory " + map.string()),
                     {map.string() + ": --trajectory would write onto the input"});
  ExpectOneLineError(RunDuskmap("localize --map " + map.string() + " --dataset " + Data() +
                                " --session A --records " + Data() + "/A/rgb.txt"),
                     {"--records would write inside the input " + Data()});
  ExpectOneLineError(RunDuskmap("map --dataset " + Data() + " --sessions 1 --output " + Data() +
                                "/manifest.json"),
                     {Data() + "/manifest.json: --output would write inside the input"});
  ExpectOneLineError(RunDuskmap("localize --map " + map.string() + " --dataset " + Data() +
                                " --session A --records " + (dir_ / "r.jsonl").string() +
                                " --summary " + (dir_ / "r.jsonl").string()),
                     {"given to both --records and --summary"});
  EXPECT_EQ(Snapshot(map), map_before);
  EXPECT_EQ(Snapshot(dir_ / "data"), data_before);
}

TEST_F(SafetyCli, MapReplacesOnlyAMapAndOnlyWithOverwrite) {
  const fs::path target = dir_ / "again.db";
  fs::copy_file(dir_ / "m.db", target, fs::copy_options::overwrite_existing);
  const auto before = Snapshot(target);
  const std::string map = "map --dataset " + Data() + " --sessions 1 --feature orb --output ";
  ExpectOneLineError(RunDuskmap(map + target.string()),
                     {target.string() + ": already exists (--output; pass --overwrite"});
  EXPECT_EQ(Snapshot(target), before);
  const fs::path notes = dir_ / "notes.db";
  std::ofstream(notes) << "my notes";
  ExpectOneLineError(RunDuskmap(map + notes.string() + " --overwrite"),
                     {notes.string() + ": not a duskmap map"});
  EXPECT_EQ(ReadText(notes), "my notes");
  const Result replaced = RunDuskmap(map + target.string() + " --overwrite");
  EXPECT_EQ(replaced.exit_code, 0) << replaced.output;
  EXPECT_FALSE(fs::exists(target.string() + ".saving"));
}

TEST_F(SafetyCli, MapAndLocalizeRefuseMeaninglessArguments) {
  const std::string map = "map --dataset " + Data() + " --output " + (dir_ / "never.db").string();
  ExpectOneLineError(RunDuskmap(map + " --sessions 1 1"), {"session '1' is given twice"});
  ExpectOneLineError(RunDuskmap(map + " --sessions 1 --feature ''"), {"--feature: empty feature type"});
  ExpectOneLineError(RunDuskmap(map + " --sessions 1 --feature OR"),
                     {"unknown feature type 'OR'", "known: ", "orb"});
  ExpectOneLineError(RunDuskmap("localize --map " + (dir_ / "m.db").string() + " --dataset " + Data() +
                                " --session A --odometry-cache -5"),
                     {"--odometry-cache: must be in [0, 100000], got -5"});
  EXPECT_FALSE(fs::exists(dir_ / "never.db"));
}

TEST_F(SafetyCli, ALocalizeWriteCutShortLeavesTheOldRecords) {
  const fs::path records = dir_ / "cut.jsonl";
  std::ofstream(records) << "old records\n";
  // A 1-KiB file-size limit (SIGXFSZ ignored) makes the write fail part
  // way, as a full disk does.
  const Result r = RunDuskmap("localize --map " + (dir_ / "m.db").string() + " --dataset " + Data() +
                                  " --session A --records " + records.string(),
                              "trap '' XFSZ; ulimit -f 1; ");
  ExpectOneLineError(r, {records.string() + ": cannot write: File too large (nothing was changed)"});
  EXPECT_EQ(ReadText(records), "old records\n");
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find("cut.jsonl.partial"), std::string::npos);
  }
}

TEST_F(SafetyCli, ResumeRefusesAnyOtherConfiguration) {
  const std::string config = WriteExperiment("resume.json", Experiment());
  ASSERT_EQ(RunDuskmap(Run(config, "resume")).exit_code, 0);
  const fs::path out = dir_ / "resume";
  const auto before = Snapshot(out / "run.json");
  const auto cells = ReadText(out / "report" / "cells.csv");

  // An engine config that changes a result.
  std::ofstream(dir_ / "engine60.json") << R"({"registration": {"min_inliers": 60}})";
  nlohmann::json changed = Experiment();
  changed["engine_config"] = (dir_ / "engine60.json").string();
  WriteExperiment("resume.json", changed);
  ExpectOneLineError(RunDuskmap(Run(config, "resume", "--resume")),
                     {(out / "run.json").string(), "another configuration, first at",
                      "first at engine (earlier null, now {"});
  changed = Experiment();
  changed["frame_step"] = 2;
  WriteExperiment("resume.json", changed);
  ExpectOneLineError(RunDuskmap(Run(config, "resume", "--resume")),
                     {"first at experiment.frame_step (absent earlier, now 2)"});
  changed = Experiment();
  changed["maps"] = {"1"};
  WriteExperiment("resume.json", changed);
  ExpectOneLineError(RunDuskmap(Run(config, "resume", "--resume")), {"first at experiment.maps"});
  EXPECT_EQ(Snapshot(out / "run.json"), before);
  EXPECT_EQ(ReadText(out / "report" / "cells.csv"), cells);

  WriteExperiment("resume.json", Experiment());
  ExpectOneLineError(RunDuskmap(Run(config, "resume", "--resume --overwrite")),
                     {"--resume and --overwrite: give one"});
  const Result resumed = RunDuskmap(Run(config, "resume", "--resume"));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(ReadText(out / "report" / "cells.csv"), cells);
}

TEST_F(SafetyCli, RunRefusesFoldersItDidNotWriteAndLockedFolders) {
  const std::string config = WriteExperiment("plain.json", Experiment());
  const fs::path mine = UserFolder("mine_run");
  const auto before = Snapshot(mine);
  for (const char* flag : {"", "--overwrite"}) {
    ExpectOneLineError(RunDuskmap(Run(config, "mine_run", flag)),
                       {mine.string() + ": not a duskmap results folder (no run.json)"});
  }
  EXPECT_EQ(Snapshot(mine), before);
  EXPECT_FALSE(fs::exists(mine / "jobs"));

  // Another process writing the folder: the lock refuses a second run.
  const fs::path busy = dir_ / "busy";
  fs::create_directories(busy);
  {
    duskmap::FolderLock held(busy);
    ExpectOneLineError(RunDuskmap(Run(config, "busy")),
                       {busy.string() + ": another duskmap process (pid " + std::to_string(::getpid())});
    EXPECT_FALSE(fs::exists(busy / "jobs"));
  }
  const Result free = RunDuskmap(Run(config, "busy"));
  EXPECT_EQ(free.exit_code, 0) << free.output;
}

TEST_F(SafetyCli, ExperimentConfigsAreCheckedBeforeAnyJob) {
  struct Case {
    std::string name;
    std::string json;  // the config text (duplicate keys need text)
    std::vector<std::string> needles;
  };
  const std::string dataset = R"("dataset": {"path": ")" + Data() + R"(", "format": "synthetic"})";
  const std::vector<Case> cases = {
      {"escape", "{" + dataset + R"(, "features": ["OR"], "maps": ["../../../../../escaped"], "localization_sessions": ["A"]})",
       {"maps: '../../../../../escaped' cannot name a results folder"}},
      {"unknown_session", "{" + dataset + R"(, "features": ["OR"], "maps": ["1+Z"], "localization_sessions": ["A"]})",
       {"maps '1+Z': session 'Z' is not in the dataset", "(it has: 1 2 A)"}},
      {"duplicate_key", "{" + dataset + R"(, "features": ["OR"], "maps": ["1"], "localization_sessions": ["A"], "frame_step": 1, "frame_step": 2})",
       {"key 'frame_step' is given twice"}},
      {"wrapped_int", "{" + dataset + R"(, "features": ["OR"], "maps": ["1"], "localization_sessions": ["A"], "frame_step": 4294967298})",
       {"frame_step: 4294967298 is out of range"}},
      {"fraction", "{" + dataset + R"(, "features": ["OR"], "maps": ["1"], "localization_sessions": ["A"], "frame_step": 1.5})",
       {"frame_step: expected an integer, got 1.5"}},
      {"duplicate_map", "{" + dataset + R"(, "features": ["OR"], "maps": ["1", "1"], "localization_sessions": ["A"]})",
       {"maps: '1' listed twice"}},
      {"duplicate_session", "{" + dataset + R"(, "features": ["OR"], "maps": ["1"], "localization_sessions": ["A", "A"]})",
       {"localization_sessions: 'A' listed twice"}},
      {"own_session", "{" + dataset + R"(, "features": ["OR"], "maps": ["1+A"], "localization_sessions": ["A"]})",
       {"'A' is also a session of map '1+A'"}},
      {"gap_classes", "{" + dataset + R"(, "features": ["OR"], "consecutive": {"pairs": [["1", "2"]], "gap_classes_min": [-30]}})",
       {"consecutive.gap_classes_min: minutes must be increasing"}},
      {"clock_unknown", "{" + dataset + R"(, "features": ["OR"], "maps": ["1"], "localization_sessions": ["A"], "session_clock_times": {"Q": "17:00"}})",
       {"session_clock_times: session 'Q' is not in the dataset"}},
      {"invalid", "{" + dataset + ",\n \"features\": [\"OR\"\n}", {":3:1: invalid JSON ("}},
  };
  for (const Case& c : cases) {
    const fs::path path = dir_ / (c.name + ".json");
    std::ofstream(path) << c.json;
    std::vector<std::string> needles = c.needles;
    needles.push_back(path.string());
    SCOPED_TRACE(c.name);
    ExpectOneLineError(RunDuskmap(Run(path.string(), "out_" + c.name)), needles);
    EXPECT_FALSE(fs::exists(dir_ / ("out_" + c.name))) << "no job ran";
  }
  EXPECT_FALSE(fs::exists(dir_.parent_path().parent_path() / "escaped"));
  // Engine option errors name the file and the JSON section, not a C++ struct.
  std::ofstream(dir_ / "engine_bad.json") << R"({"registration": {"guess_window_px": -1}})";
  const Result engine = RunDuskmap("map --dataset " + Data() + " --sessions 1 --config " +
                                   (dir_ / "engine_bad.json").string() + " --output " +
                                   (dir_ / "never.db").string());
  ExpectOneLineError(engine, {(dir_ / "engine_bad.json").string() + ": registration.guess_window_px: "});
}

TEST_F(SafetyCli, ReportRefusesAnotherConfigAndForeignFolders) {
  const std::string config = WriteExperiment("report_run.json", Experiment());
  ASSERT_EQ(RunDuskmap(Run(config, "report_run")).exit_code, 0);
  nlohmann::json other = Experiment();
  other["features"] = {"BF"};
  const std::string other_config = WriteExperiment("report_other.json", other);
  const std::string results = (dir_ / "report_run").string();
  ExpectOneLineError(RunDuskmap("report " + other_config + " --results " + results + " --output " +
                                (dir_ / "rep").string() + " --no-figures"),
                     {other_config + ": not the config of the run in", "features"});
  const fs::path mine = UserFolder("mine_report");
  const auto before = Snapshot(mine);
  ExpectOneLineError(RunDuskmap("report " + config + " --results " + results + " --output " +
                                mine.string() + " --no-figures"),
                     {mine.string() + ": exists and is not an earlier report"});
  EXPECT_EQ(Snapshot(mine), before);
  const Result ok = RunDuskmap("report " + config + " --results " + results + " --output " +
                               (dir_ / "report_run" / "report").string() + " --no-figures");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

}  // namespace
