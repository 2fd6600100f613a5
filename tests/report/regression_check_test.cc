#include "slam/report/regression_check.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
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
    EXPECT_NE(std::string(e.what()).find(path.string() +
                                         ":2: relocalized_pct: 'seventy' is not a number"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(path) << "a,b\n1,2\n";
  EXPECT_THROW(ReadCellRates(path.string()), InputError);
  fs::remove(path);
  EXPECT_THROW(ReadCellRates(path.string()), InputError);
}

// check-rates is a CI gate: a file a broken run wrote must not pass it. NaN,
// infinity and 150 % were read as rates (inf and 150 counted as
// improvements), and a cell listed twice was accepted.
TEST(RegressionCheck, RefusesRatesThatNoReportWrites) {
  const std::string path = testing::ProcessTempPath("bad_cells.csv");
  const std::string header = "feature,row,session,job,frames,relocalized_pct,correct_pct,wrong\n";
  const auto error = [&](const std::string& rows) {
    std::ofstream(path) << header << rows;
    return testing::ErrorOf([&] { ReadCellRates(path); });
  };
  EXPECT_EQ(error("SI,1,A,j,40,nan,70,1\n"), path + ":2: relocalized_pct: 'nan' is not a finite number");
  EXPECT_EQ(error("SI,1,A,j,40,NaN,70,1\n"), path + ":2: relocalized_pct: 'NaN' is not a finite number");
  EXPECT_EQ(error("SI,1,A,j,40,50,inf,1\n"), path + ":2: correct_pct: 'inf' is not a finite number");
  EXPECT_EQ(error("SI,1,A,j,40,-infinity,70,1\n"),
            path + ":2: relocalized_pct: '-infinity' is not a finite number");
  EXPECT_EQ(error("SI,1,A,j,40,1e400,70,1\n"), path + ":2: relocalized_pct: '1e400' is out of range");
  EXPECT_EQ(error("SI,1,A,j,40,150,70,1\n"), path + ":2: relocalized_pct: 150 is outside [0, 100]");
  EXPECT_EQ(error("SI,1,A,j,40,50,-0.5,1\n"), path + ":2: correct_pct: -0.5 is outside [0, 100]");
  EXPECT_EQ(error("SI,1,A,j,40,-3,70,1\n"), path + ":2: relocalized_pct: -3 is outside [0, 100]");
  EXPECT_EQ(error("SI,1,A,j,0,50,70,0\n"),
            path + ":2: frames: 0 is not a whole number in [1, 2147483647]");
  EXPECT_EQ(error("SI,1,A,j,40.5,50,70,0\n"),
            path + ":2: frames: 40.5 is not a whole number in [1, 2147483647]");
  EXPECT_EQ(error("SI,1,A,j,40,50,70,41\n"), path + ":2: wrong: 41 is not a whole number in [0, 40]");
  EXPECT_EQ(error("SI,1,A,j,40,50,70,nan\n"), path + ":2: wrong: 'nan' is not a finite number");
  // The same cell twice, even with the same values: which one would count?
  EXPECT_EQ(error("SI,\"1\",A,j,40,50,70,1\nOR,\"1\",A,j,40,50,70,1\n\nSI,\"1\",A,j,40,50,70,1\n"),
            path + ":5: cell 'SI 1 A' is listed twice (first on line 2)");
  std::ofstream(path) << "feature,row,session,frames,frames,relocalized_pct,correct_pct,wrong\n";
  EXPECT_EQ(testing::ErrorOf([&] { ReadCellRates(path); }),
            path + ":1: column 'frames' is given twice");
  // The report's own values pass: -1 without ground truth, 0 and 100.
  EXPECT_EQ(error("SI,1,A,j,40,0,-1,0\nSI,2,A,j,40,100,100,0\n"), "");
}

TEST(RegressionCheck, ParsesTextAlreadyOpen) {
  std::istringstream in("feature,row,session,frames,relocalized_pct,correct_pct,wrong\r\n"
                        "SI,1,A,10,50,40,1\r\n");
  const std::vector<CellRates> cells = ParseCellRates(in, "text");
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].wrong, 1);
  std::istringstream empty("");
  EXPECT_EQ(testing::ErrorOf([&] { ParseCellRates(empty, "text"); }), "text: empty file");
}

}  // namespace
}  // namespace duskmap
