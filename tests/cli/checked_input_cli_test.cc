// End-to-end: numbers and JSON are checked where they enter (issue 48, items
// 3 and 4). JSON nested '[' * 200000 deep crashed every reader with SIGSEGV,
// 1e400 in a config was an "internal error", and check-rates let NaN, inf,
// 150 % and duplicate rows through. Every case: exit code 1 and one line
// naming the file and the problem.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"
#include "tests/testing/temp_dir.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;
using duskmap::testing::ExpectOneLineError;

constexpr const char* kTooDeep = "arrays and objects nested deeper than 64 levels";

class CheckedInputCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("checked_input_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(dir_.string(), 6, {"1", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
    const nlohmann::json experiment = {{"dataset", {{"path", Data()}, {"format", "synthetic"}}},
                                       {"features", {"OR"}},
                                       {"maps", {"1"}},
                                       {"localization_sessions", {"A"}}};
    std::ofstream(Config()) << experiment.dump(2);
    const Result run = RunDuskmap("run " + Config() + " --output " + Results() +
                                  " --jobs 2 --no-figures");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ofstream(Deep()) << std::string(200000, '[') << std::string(200000, ']');
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string Data() { return (dir_ / "data").string(); }
  static std::string Config() { return (dir_ / "experiment.json").string(); }
  static std::string Results() { return (dir_ / "results").string(); }
  static std::string Deep() { return (dir_ / "deep.json").string(); }
  // A copy of the results folder with `file` (relative) replaced by `text`.
  static std::string ResultsWith(const std::string& name, const std::string& file,
                                 const std::string& text) {
    const fs::path copy = dir_ / name;
    fs::copy(Results(), copy, fs::copy_options::recursive);
    std::ofstream(copy / file) << text;
    return copy.string();
  }

  static fs::path dir_;
};

fs::path CheckedInputCli::dir_;

TEST_F(CheckedInputCli, DeeplyNestedJsonIsAOneLineErrorInEveryReader) {
  const std::string deep = Deep();
  const std::vector<std::string> needles = {deep + ": " + kTooDeep};
  SCOPED_TRACE("run: the experiment config");
  ExpectOneLineError(RunDuskmap("run " + deep + " --output " + (dir_ / "never").string()), needles);
  EXPECT_FALSE(fs::exists(dir_ / "never"));
  SCOPED_TRACE("map: the engine config");
  ExpectOneLineError(RunDuskmap("map --dataset " + Data() + " --sessions 1 --config " + deep +
                                " --output " + (dir_ / "never.db").string()),
                     needles);
  SCOPED_TRACE("generate: the generator config");
  ExpectOneLineError(RunDuskmap("generate --config " + deep + " --output " +
                                (dir_ / "never_data").string()),
                     needles);
  SCOPED_TRACE("features eval: the feature options");
  ExpectOneLineError(RunDuskmap("features eval --data " + Data() + " --types orb --config " + deep),
                     needles);
  SCOPED_TRACE("report: the experiment config");
  ExpectOneLineError(RunDuskmap("report " + deep + " --results " + Results() + " --output " +
                                (dir_ / "never_report").string() + " --no-figures"),
                     needles);

  SCOPED_TRACE("a dataset's manifest.json");
  const fs::path dataset = dir_ / "deep_dataset";
  fs::create_directories(dataset);
  std::string objects;
  for (int i = 0; i < 100000; ++i) objects += "{\"format\": ";
  std::ofstream(dataset / "manifest.json") << objects;
  ExpectOneLineError(RunDuskmap("map --dataset " + dataset.string() + " --sessions 1 --output " +
                                (dir_ / "never2.db").string()),
                     {(dataset / "manifest.json").string() + ": " + kTooDeep});

  SCOPED_TRACE("report: a job summary");
  const std::string summary = "jobs/localize/OR/1/A/summary.json";
  const std::string bad_summary = ResultsWith("deep_summary", summary, std::string(200000, '['));
  ExpectOneLineError(RunDuskmap("report " + Config() + " --results " + bad_summary + " --output " +
                                (dir_ / "never_report2").string() + " --no-figures"),
                     {bad_summary + "/" + summary + ": " + kTooDeep});

  SCOPED_TRACE("report: a results folder's run.json");
  const std::string bad_manifest = ResultsWith("deep_manifest", "run.json", std::string(200000, '['));
  ExpectOneLineError(RunDuskmap("report " + Config() + " --results " + bad_manifest + " --output " +
                                (dir_ / "never_report3").string() + " --no-figures"),
                     {bad_manifest + "/run.json: " + kTooDeep});
}

TEST_F(CheckedInputCli, NumbersBeyondDoublesRangeAreNamedByFileAndKey) {
  nlohmann::json experiment = nlohmann::json::parse(std::ifstream(Config()));
  experiment["frame_step"] = 1;
  std::string text = experiment.dump(2);
  text.replace(text.find("\"frame_step\": 1"), 15, "\"frame_step\": 1e400");
  const fs::path config = dir_ / "overflow.json";
  std::ofstream(config) << text;
  ExpectOneLineError(RunDuskmap("run " + config.string() + " --output " + (dir_ / "never3").string()),
                     {config.string() + ": frame_step: number out of range (1e400)"});
  const fs::path engine = dir_ / "engine_overflow.json";
  std::ofstream(engine) << R"({"registration": {"guess_window_px": -1E+999}})";
  ExpectOneLineError(RunDuskmap("map --dataset " + Data() + " --sessions 1 --config " +
                                engine.string() + " --output " + (dir_ / "never4.db").string()),
                     {engine.string() + ": registration.guess_window_px: number out of range (-1E+999)"});
}

// check-rates is the CI gate: a broken run's cells.csv must not pass it.
TEST_F(CheckedInputCli, CheckRatesRefusesNanInfOutOfRangeAndDuplicateRows) {
  const std::string baseline = Results() + "/report/cells.csv";
  std::ifstream in(baseline);
  std::string header, row;
  ASSERT_TRUE(std::getline(in, header) && std::getline(in, row)) << baseline;
  const Result same = RunDuskmap("check-rates --baseline " + baseline + " --current " + baseline);
  EXPECT_EQ(same.exit_code, 0) << same.output;

  // The row's relocalized_pct (6th field) replaced by `value`.
  const auto with_rate = [&](const std::string& value) {
    std::vector<std::string> fields;
    std::stringstream split(row);
    for (std::string field; std::getline(split, field, ',');) fields.push_back(field);
    fields[5] = value;
    std::string line;
    for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
    return line;
  };
  const std::string current = (dir_ / "current_cells.csv").string();
  const auto check = [&](const std::string& body) {
    std::ofstream(current) << header << "\n" << body << "\n";
    return RunDuskmap("check-rates --baseline " + baseline + " --current " + current);
  };
  ExpectOneLineError(check(with_rate("nan")), {current + ":2: relocalized_pct: 'nan' is not a finite number"});
  ExpectOneLineError(check(with_rate("inf")), {current + ":2: relocalized_pct: 'inf' is not a finite number"});
  ExpectOneLineError(check(with_rate("150")), {current + ":2: relocalized_pct: 150 is outside [0, 100]"});
  ExpectOneLineError(check(row + "\n" + row), {current + ":3: cell '", "is listed twice (first on line 2)"});
  // The baseline is checked the same way.
  const Result bad_baseline = RunDuskmap("check-rates --baseline " + current + " --current " + baseline);
  ExpectOneLineError(bad_baseline, {current + ":3: cell '"});
}

}  // namespace
