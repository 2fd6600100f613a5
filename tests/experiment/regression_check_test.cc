#include "slam/experiment/regression_check.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

CellRates Cell(const std::string& row, double relocalized, double correct, int wrong,
               int frames = 100) {
  CellRates cell;
  cell.feature = "SI";
  cell.row = row;
  cell.session = "A";
  cell.frames = frames;
  cell.relocalized_pct = relocalized;
  cell.correct_pct = correct;
  cell.wrong = wrong;
  return cell;
}

TEST(RegressionCheck, DropsBeyondTheToleranceFail) {
  const std::vector<CellRates> baseline = {Cell("1", 80, 78, 1), Cell("1+6", 90, 88, 0)};
  RegressionOptions options;
  options.tolerance_pct = 5.0;
  // Within tolerance both ways.
  RegressionResult r = CompareCellRates(baseline, {Cell("1", 75.5, 74, 2), Cell("1+6", 94, 92, 0)},
                                        options);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.cells_compared, 2);
  EXPECT_TRUE(r.improvements.empty());
  // A re-localization rate dropped 6 points.
  r = CompareCellRates(baseline, {Cell("1", 74, 74, 1), Cell("1+6", 90, 88, 0)}, options);
  ASSERT_EQ(r.regressions.size(), 1u);
  EXPECT_EQ(r.regressions[0].key, "SI 1 A");
  EXPECT_EQ(r.regressions[0].metric, "relocalized_pct");
  // Same rate, but correct ones replaced by wrong ones.
  r = CompareCellRates(baseline, {Cell("1", 80, 70, 9), Cell("1+6", 90, 88, 0)}, options);
  ASSERT_EQ(r.regressions.size(), 2u);
  EXPECT_EQ(r.regressions[0].metric, "correct_pct");
  EXPECT_EQ(r.regressions[1].metric, "wrong_pct");
  // Improvements are reported, not failed.
  r = CompareCellRates(baseline, {Cell("1", 95, 93, 1), Cell("1+6", 90, 88, 0)}, options);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.improvements.size(), 2u);
}

TEST(RegressionCheck, MissingCellsOrOtherFrameCountsFail) {
  const std::vector<CellRates> baseline = {Cell("1", 80, 78, 1), Cell("1+6", 90, 88, 0)};
  RegressionResult r = CompareCellRates(baseline, {Cell("1", 80, 78, 1)}, RegressionOptions());
  ASSERT_EQ(r.regressions.size(), 1u);
  EXPECT_EQ(r.regressions[0].metric, "missing");
  r = CompareCellRates(baseline, {Cell("1", 80, 78, 1), Cell("1+6", 90, 88, 0, 50)},
                       RegressionOptions());
  ASSERT_EQ(r.regressions.size(), 1u);
  EXPECT_EQ(r.regressions[0].key, "SI 1+6 A");
  RegressionOptions bad;
  bad.tolerance_pct = -1;
  EXPECT_THROW(CompareCellRates(baseline, baseline, bad), ConfigError);
}

TEST(RegressionCheck, ReadsTheReportsCellsCsv) {
  const fs::path path = testing::ProcessTempPath("cells.csv");
  std::ofstream(path) << "feature,row,session,job,frames,relocalized_pct,correct_pct,wrong,"
                         "no_candidate_pct,mean_inliers_pct,mean_jump_mm\n"
                         "SI,\"1|2|3\",A,localize/SI/1/A,40,72.5,70,1,5,20,30\n"
                         "OR,\"1\",B,localize/OR/1/B,40,10,-1,0,5,20,30\n";
  const std::vector<CellRates> cells = ReadCellRates(path.string());
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].row, "1|2|3");
  EXPECT_DOUBLE_EQ(cells[0].relocalized_pct, 72.5);
  EXPECT_EQ(cells[0].wrong, 1);
  EXPECT_LT(cells[1].correct_pct, 0.0);

  std::ofstream(path) << "feature,row,session,job,frames,relocalized_pct,correct_pct,wrong\n"
                         "SI,1,A,j,40,seventy,70,1\n";
  try {
    ReadCellRates(path.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ":2: 'seventy' is not a number"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(path) << "a,b\n1,2\n";
  EXPECT_THROW(ReadCellRates(path.string()), InputError);
  fs::remove(path);
  EXPECT_THROW(ReadCellRates(path.string()), InputError);
}

}  // namespace
}  // namespace duskmap
