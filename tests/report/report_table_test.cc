#include "slam/report/report_table.h"

#include <gtest/gtest.h>

#include "slam/report/paper_reference.h"

namespace duskmap {
namespace {

TEST(ReportTable, WritesMeasuredBesidePaper) {
  ReportTable table("relocalization_pct", "Re-localization (%)", {"1", "1|2"}, {"SU", "SI"});
  table.SetMeasured("1", "SU", 71.4);
  table.SetPaper("1", "SU", 68);
  table.SetMeasured("1|2", "SI", 90);
  const std::string markdown = table.ToMarkdown();
  EXPECT_NE(markdown.find("| 1 | 71 (68) | – |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| 1\\|2 | – | 90 |"), std::string::npos) << markdown;
  EXPECT_NE(table.ToCsv().find("\"1\",SU,71.40,68.00"), std::string::npos);
  const std::string latex = table.ToLatex();
  EXPECT_NE(latex.find("1$|$2 & -- & 90 \\\\"), std::string::npos) << latex;
}

TEST(PaperReference, LooksUpPaperTables) {
  const PaperReference paper =
      PaperReference::Load(std::string(DUSKMAP_SOURCE_DIR) + "/configs/paper_results.json");
  EXPECT_EQ(paper.Value({"table_cumulative_relocalization", "relocalization_pct", "1+6"}, "SU"),
            94.0);
  EXPECT_EQ(paper.Value({"table_ram_mb", "nodes", "1+6"}, "SI"), 436.0);  // per map, any column
  EXPECT_EQ(paper.Value({"table_cumulative_relocalization", "relocalization_pct", "1"}, "OR"),
            std::nullopt);  // the paper did not run ORB
  EXPECT_EQ(paper.Value({"no_such_table"}, "SU"), std::nullopt);

  ReportTable table("relocalization_pct", "Re-localization (%)", {"1", "1+6"}, {"SU", "OR"});
  paper.FillRows("table_cumulative_relocalization", "relocalization_pct", &table);
  EXPECT_EQ(table.At("1", "SU").paper, 68.0);
  EXPECT_FALSE(table.At("1", "OR").paper.has_value());
  EXPECT_FALSE(table.At("1", "SU").measured.has_value());
}

}  // namespace
}  // namespace duskmap
