#include "slam/report/scaling_tables.h"

#include <gtest/gtest.h>

#include "slam/report/report_builder.h"
#include "slam/report/report_cells.h"
#include "slam/report/report_table_ids.h"

namespace duskmap {
namespace {

// Maps 1, 1-2 and 1-2-3 on the curve (and 2, off it), sessions A and B
// localized on each, features SI and OR.
ExperimentOptions CurveOptions() {
  ExperimentOptions options;
  options.dataset_path = "d";
  options.features = {"SI", "OR"};
  for (const char* label : {"1", "2", "1-2", "1-2-3"}) options.maps.push_back(ParseMapSpec(label));
  options.localization_sessions = {"A", "B"};
  options.scaling = ScalingCurve{{"1", "1-2", "1-2-3"}};
  return options;
}

// Synthetic summaries whose numbers follow the map's session count n: on
// each map, A loads it (0.5 n s) and B shares the loaded copy; LCD + TE is
// 10 n ms for A and 10 n + 2 ms for B; the localizer holds n MiB; A
// re-localizes 40 + n frames of 100, B 60 + n, 30 of each correct.
ExperimentResults CurveResults(const ExperimentOptions& options) {
  ExperimentResults results;
  for (const std::string& feature : options.features) {
    for (const MapSpec& map : options.maps) {
      const int n = static_cast<int>(map.sessions.size());
      MapJobSummary m;
      m.num_nodes = 100 * n;
      results.maps["map/" + feature + "/" + map.label] = m;
      for (const std::string& session : options.localization_sessions) {
        const bool a = session == "A";
        LocalizationJobSummary s;
        s.num_frames = 100;
        s.num_relocalized = (a ? 40 : 60) + n;
        s.has_ground_truth = true;
        s.num_within_threshold = {20, 30, 40};
        s.median_lcd_te_ms = 10.0 * n + (a ? 0.0 : 2.0);
        s.mean_times_ms.loop_closure_detection = 4.0 * n;
        s.mean_times_ms.transformation_estimation = 6.0 * n;
        s.memory_bytes = {{"descriptors", static_cast<size_t>(n) << 20}};
        s.map_from_cache = !a;
        s.map_load_s = a ? 0.5 * n : 0.0;
        s.localizer_setup_s = a ? 0.1 : 0.3;
        results.localization["localize/" + feature + "/" + map.label + "/" + session] = s;
      }
    }
  }
  return results;
}

ExperimentReport CurveReport(const ExperimentOptions& options) {
  const ExperimentPlan plan = PlanExperiment(options, {});
  return BuildReport(options, plan, CurveResults(options), std::nullopt);
}

TEST(BuildScalingSection, OneTablePerMeasureWithTheCurvesMapsAsRows) {
  const ExperimentReport report = CurveReport(CurveOptions());
  const std::vector<std::string> rows = {"1 (1)", "2 (1-2)", "3 (1-2-3)"};
  for (const char* id : {kTableScalingNodes, kTableScalingLcdTeMs, kTableScalingMemoryMb,
                         kTableScalingMapOpenS, kTableScalingRelocalizationPct,
                         kTableScalingCorrectPct}) {
    const ReportTable* table = FindTable(report.tables, id);
    ASSERT_NE(table, nullptr) << id;
    EXPECT_EQ(table->rows(), rows) << id;
    EXPECT_EQ(table->columns(), (std::vector<std::string>{"SI", "OR"})) << id;
  }
  const auto at = [&report](const char* id, const std::string& row) {
    return *CellValue(FindTable(report.tables, id), row, "OR", TableSide::kMeasured);
  };
  for (int n = 1; n <= 3; ++n) {
    const std::string row = rows[n - 1];
    EXPECT_DOUBLE_EQ(at(kTableScalingNodes, row), 100.0 * n);
    EXPECT_DOUBLE_EQ(at(kTableScalingLcdTeMs, row), 10.0 * n + 1.0);  // mean of A's and B's medians
    EXPECT_DOUBLE_EQ(at(kTableScalingMemoryMb, row), 1.0 * n);
    // The load of the job that loaded the map, plus the mean setup.
    EXPECT_DOUBLE_EQ(at(kTableScalingMapOpenS, row), 0.5 * n + 0.2);
    EXPECT_DOUBLE_EQ(at(kTableScalingRelocalizationPct, row), 50.0 + n);
    EXPECT_DOUBLE_EQ(at(kTableScalingCorrectPct, row), 30.0);
  }
}

TEST(BuildScalingSection, TakesTheReportTablesCellsForTheSameMeasures) {
  const ExperimentReport report = CurveReport(CurveOptions());
  const std::vector<std::pair<const char*, const char*>> same = {
      {kTableScalingNodes, kTableGraphNodes},
      {kTableScalingMemoryMb, kTableMemoryMb},
      {kTableScalingRelocalizationPct, kTableRelocalizationPct},
      {kTableScalingCorrectPct, kTableCorrectPct}};
  for (const auto& [scaling, own] : same) {
    for (const auto& [row, label] : {std::pair<std::string, std::string>{"2 (1-2)", "1-2"},
                                     {"3 (1-2-3)", "1-2-3"}}) {
      EXPECT_EQ(CellValue(FindTable(report.tables, scaling), row, "SI", TableSide::kMeasured),
                CellValue(FindTable(report.tables, own), label, "SI", TableSide::kMeasured))
          << scaling << " " << row;
    }
  }
}

TEST(BuildScalingSection, WritesTheFiguresDataPerFeatureInTheCurvesOrder) {
  const ExperimentOptions options = CurveOptions();
  const ExperimentPlan plan = PlanExperiment(options, {});
  const ExperimentReport report = CurveReport(options);
  const ScalingSection section =
      BuildScalingSection(options, plan, CurveResults(options).localization, report.tables);
  ASSERT_EQ(section.points.size(), 6u);
  EXPECT_EQ(section.points[3].feature, "OR");
  EXPECT_EQ(section.points[3].map, "1");
  EXPECT_DOUBLE_EQ(*section.points[5].map_load_s, 1.5);
  EXPECT_DOUBLE_EQ(*section.points[5].localizer_setup_s, 0.2);
  EXPECT_DOUBLE_EQ(*section.points[5].lcd_ms, 12.0);
  EXPECT_DOUBLE_EQ(*section.points[5].te_ms, 18.0);
  EXPECT_EQ(section.csv.substr(0, section.csv.find('\n')),
            "feature,map,sessions,nodes,lcd_te_ms,lcd_ms,te_ms,memory_mb,map_load_s,"
            "localizer_setup_s,map_open_s,relocalized_pct,correct_pct");
  EXPECT_NE(section.csv.find("\nSI,\"1-2\",2,200,21,8,12,2,1,0.2,1.2,52,30\n"), std::string::npos)
      << section.csv;
  EXPECT_EQ(report.scaling_csv, section.csv);
}

TEST(BuildScalingSection, LeavesAMeasureNoJobMeasuredEmpty) {
  const ExperimentOptions options = CurveOptions();
  ExperimentResults results = CurveResults(options);
  results.localization.erase("localize/SI/1-2-3/A");  // the job that loaded the map
  results.localization.erase("localize/SI/1-2/A");
  results.localization.erase("localize/SI/1-2/B");
  const ExperimentReport report =
      BuildReport(options, PlanExperiment(options, {}), results, std::nullopt);
  const auto cell = [&report](const char* id, const std::string& row) {
    return CellValue(FindTable(report.tables, id), row, "SI", TableSide::kMeasured);
  };
  EXPECT_FALSE(cell(kTableScalingMapOpenS, "3 (1-2-3)").has_value());  // B shared the copy
  EXPECT_DOUBLE_EQ(*cell(kTableScalingLcdTeMs, "3 (1-2-3)"), 32.0);
  EXPECT_FALSE(cell(kTableScalingLcdTeMs, "2 (1-2)").has_value());
  EXPECT_FALSE(cell(kTableScalingRelocalizationPct, "2 (1-2)").has_value());
  EXPECT_DOUBLE_EQ(*cell(kTableScalingNodes, "2 (1-2)"), 200.0);  // the map job ran
  EXPECT_NE(report.scaling_csv.find("\nSI,\"1-2\",2,200,,,,"), std::string::npos)
      << report.scaling_csv;
}

TEST(BuildScalingSection, NothingWithoutACurve) {
  ExperimentOptions options = CurveOptions();
  options.scaling.reset();
  const ScalingSection section = BuildScalingSection(options, PlanExperiment(options, {}),
                                                     CurveResults(options).localization, {});
  EXPECT_TRUE(section.tables.empty());
  EXPECT_TRUE(section.points.empty());
  EXPECT_TRUE(section.csv.empty());
}

TEST(ScalingRowLabels, SessionCountAndLabelLongLabelsShortened) {
  std::string reduced = "a1";
  for (const char* s : {"a2", "b1", "b2", "c1", "c2", "d1", "d2", "e1", "h6"}) {
    reduced += std::string("-") + s;
  }
  EXPECT_EQ(ScalingRowLabels({ParseMapSpec("a1"), ParseMapSpec("a1+a2"), ParseMapSpec(reduced)}),
            (std::vector<std::string>{"1 (a1)", "2 (a1+a2)", "10 (a1-...-h6)"}));
  // Two long labels that would read the same shortened keep their full labels.
  std::string other = "a1";
  for (const char* s : {"a3", "b1", "b2", "c1", "c2", "d1", "d2", "e1", "h6"}) {
    other += std::string("-") + s;
  }
  EXPECT_EQ(ScalingRowLabels({ParseMapSpec(reduced), ParseMapSpec(other)}),
            (std::vector<std::string>{"10 (" + reduced + ")", "10 (" + other + ")"}));
}

}  // namespace
}  // namespace duskmap
