#include "slam/report/experiment_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

using testing::ErrorOf;
using testing::ProcessTempDir;

// The results folder of a run of features SI and OR (OR skipped) whose jobs
// have not run yet: run.json only.
fs::path UnfinishedRun(const fs::path& root, const fs::path& config) {
  std::ofstream(config) << R"({"dataset": {"path": "data", "format": "synthetic"},
    "features": ["SI", "OR"], "maps": ["1"], "localization_sessions": ["A"]})";
  const fs::path results = root / "results";
  fs::create_directories(results);
  RunManifest manifest;
  manifest.config_path = config.string();
  manifest.dataset_path = "data";
  manifest.features = {"SI"};
  manifest.skipped_features = {{"OR", "not wanted here"}};
  manifest.session_clock = {{"1", 16 * 60 + 46}, {"A", 16 * 60 + 51}};
  WriteRunManifest(manifest, results);
  return results;
}

TEST(ExperimentReport, WritesTheTablesAndReturnsWhatTheCliPrints) {
  const fs::path root = ProcessTempDir("experiment_report");
  ExperimentReportRequest request;
  request.config_path = (root / "matrix.json").string();
  request.results_dirs = {UnfinishedRun(root, request.config_path)};
  request.output_dir = root / "report";
  request.figures = false;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const ExperimentReportOutcome outcome = WriteExperimentReport(request);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");  // the library prints nothing
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(outcome.skipped_features.size(), 1u);
  EXPECT_EQ(outcome.skipped_features[0].label, "OR");
  EXPECT_EQ(outcome.skipped_features[0].reason, "not wanted here");
  EXPECT_NE(std::find(outcome.missing_jobs.begin(), outcome.missing_jobs.end(), "localize/SI/1/A"),
            outcome.missing_jobs.end());
  EXPECT_FALSE(outcome.agreement);  // no paper numbers given
  EXPECT_FALSE(outcome.figures_drawn);
  EXPECT_TRUE(fs::is_regular_file(root / "report" / "tables.md"));
  EXPECT_TRUE(fs::is_regular_file(root / "report" / "cells.csv"));
}

TEST(ExperimentReport, NoResultsFolderIsAConfigErrorAndWritesNothing) {
  const fs::path root = ProcessTempDir("experiment_report_none");
  ExperimentReportRequest request;
  request.config_path = (root / "matrix.json").string();
  request.output_dir = root / "report";
  EXPECT_EQ(ErrorOf([&] { WriteExperimentReport(request); }), "report: no results folder");
  EXPECT_FALSE(fs::exists(request.output_dir));
}

}  // namespace
}  // namespace duskmap
