#include "slam/report/scaling_tables.h"

#include <algorithm>
#include <set>
#include <sstream>

#include "slam/report/report_cells.h"
#include "slam/report/report_table_ids.h"

namespace duskmap {
namespace {

constexpr size_t kMaxRowLabelChars = 24;

char Separator(MapKind kind) {
  switch (kind) {
    case MapKind::kMerged: return '+';
    case MapKind::kReduced: return '-';
    case MapKind::kClosestInTime: return '|';
    case MapKind::kSingle: break;
  }
  return ' ';
}

std::string ShortLabel(const MapSpec& map) {
  if (map.label.size() <= kMaxRowLabelChars || map.sessions.size() < 3) return map.label;
  const char sep = Separator(map.kind);
  return map.sessions.front() + sep + "..." + sep + map.sessions.back();
}

std::vector<MapSpec> CurveMaps(const ExperimentOptions& options) {
  std::vector<MapSpec> curve;
  for (const std::string& label : options.scaling->maps) {
    for (const MapSpec& map : options.maps) {
      if (map.label == label) curve.push_back(map);
    }
  }
  return curve;
}

// The timings of the localization jobs on one map (its matrix cells).
void MeasureJobTimes(const ExperimentPlan& plan, const LocalizationSummaries& localization,
                     ScalingPoint* point) {
  OptionalMean lcd_te, lcd, te, load, setup;
  for (const MatrixCell& cell : plan.cells) {
    if (cell.row != point->map || cell.feature != point->feature) continue;
    const auto it = localization.find(cell.job_id);
    if (it == localization.end()) continue;
    const LocalizationJobSummary& s = it->second;
    lcd_te.Add(s.median_lcd_te_ms);
    lcd.Add(s.mean_times_ms.loop_closure_detection);
    te.Add(s.mean_times_ms.transformation_estimation);
    if (!s.map_from_cache) load.Add(s.map_load_s);
    setup.Add(s.localizer_setup_s);
  }
  point->lcd_te_ms = lcd_te.Get();
  point->lcd_ms = lcd.Get();
  point->te_ms = te.Get();
  point->map_load_s = load.Get();
  point->localizer_setup_s = setup.Get();
  if (point->map_load_s && point->localizer_setup_s) {
    point->map_open_s = *point->map_load_s + *point->localizer_setup_s;
  }
}

std::vector<ScalingPoint> MeasurePoints(const ExperimentOptions& options,
                                        const ExperimentPlan& plan,
                                        const LocalizationSummaries& localization,
                                        const std::vector<ReportTable>& tables) {
  const auto cell = [&tables](const char* id, const std::string& row, const std::string& feature) {
    return CellValue(FindTable(tables, id), row, feature, TableSide::kMeasured);
  };
  const std::vector<MapSpec> curve = CurveMaps(options);
  std::vector<ScalingPoint> points;
  for (const std::string& feature : options.features) {
    for (const MapSpec& map : curve) {
      ScalingPoint p;
      p.feature = feature;
      p.map = map.label;
      p.sessions = static_cast<int>(map.sessions.size());
      p.nodes = cell(kTableGraphNodes, map.label, feature);
      p.memory_mb = cell(kTableMemoryMb, map.label, feature);
      p.relocalized_pct = cell(kTableRelocalizationPct, map.label, feature);
      p.correct_pct = cell(kTableCorrectPct, map.label, feature);
      MeasureJobTimes(plan, localization, &p);
      points.push_back(p);
    }
  }
  return points;
}

// A measure of the curve: its table and how a point holds it.
struct ScalingMeasure {
  const char* table_id;
  const char* caption;
  int decimals;
  std::optional<double> ScalingPoint::*value;
};

const std::vector<ScalingMeasure>& Measures() {
  static const std::vector<ScalingMeasure> measures = {
      {kTableScalingNodes, "Scaling curve: nodes in the map (graph size, after reduction)", 0,
       &ScalingPoint::nodes},
      {kTableScalingLcdTeMs,
       "Scaling curve: loop closure + transformation estimation per frame (ms, median per job, "
       "mean over the map's localization jobs)",
       1, &ScalingPoint::lcd_te_ms},
      {kTableScalingMemoryMb, "Scaling curve: memory needed for localization (MB)", 1,
       &ScalingPoint::memory_mb},
      {kTableScalingMapOpenS,
       "Scaling curve: map open time (s, wall): map load + localizer setup, as in the timing "
       "budget",
       2, &ScalingPoint::map_open_s},
      {kTableScalingRelocalizationPct,
       "Scaling curve: re-localization (% of frames), cumulative over the localization sessions",
       1, &ScalingPoint::relocalized_pct},
      {kTableScalingCorrectPct,
       "Scaling curve: correct re-localizations within 0.5 m/5° (% of frames), cumulative over "
       "the localization sessions",
       1, &ScalingPoint::correct_pct},
  };
  return measures;
}

std::vector<ReportTable> Tables(const ExperimentOptions& options,
                                const std::vector<ScalingPoint>& points) {
  const std::vector<MapSpec> curve = CurveMaps(options);
  const std::vector<std::string> rows = ScalingRowLabels(curve);
  std::vector<ReportTable> tables;
  for (const ScalingMeasure& measure : Measures()) {
    ReportTable table(measure.table_id, measure.caption, rows, options.features, measure.decimals);
    for (const ScalingPoint& p : points) {
      const size_t r = std::find_if(curve.begin(), curve.end(),
                                    [&p](const MapSpec& m) { return m.label == p.map; }) -
                       curve.begin();
      if (const std::optional<double>& v = p.*measure.value) {
        table.SetMeasured(rows[r], p.feature, *v);
      }
    }
    tables.push_back(table);
  }
  return tables;
}

std::string Csv(const std::vector<ScalingPoint>& points) {
  std::ostringstream out;
  out << "feature,map,sessions,nodes,lcd_te_ms,lcd_ms,te_ms,memory_mb,map_load_s,"
         "localizer_setup_s,map_open_s,relocalized_pct,correct_pct\n";
  const auto value = [&out](const std::optional<double>& v) {
    out << ",";
    if (v) out << *v;
  };
  for (const ScalingPoint& p : points) {
    out << p.feature << ",\"" << p.map << "\"," << p.sessions;
    for (const auto& v : {p.nodes, p.lcd_te_ms, p.lcd_ms, p.te_ms, p.memory_mb, p.map_load_s,
                          p.localizer_setup_s, p.map_open_s, p.relocalized_pct, p.correct_pct}) {
      value(v);
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace

std::vector<std::string> ScalingRowLabels(const std::vector<MapSpec>& curve) {
  const auto labels = [&curve](bool shorten) {
    std::vector<std::string> rows;
    for (const MapSpec& map : curve) {
      rows.push_back(std::to_string(map.sessions.size()) + " (" +
                     (shorten ? ShortLabel(map) : map.label) + ")");
    }
    return rows;
  };
  std::vector<std::string> rows = labels(true);
  const std::set<std::string> distinct(rows.begin(), rows.end());
  return distinct.size() == rows.size() ? rows : labels(false);
}

ScalingSection BuildScalingSection(const ExperimentOptions& options, const ExperimentPlan& plan,
                                   const LocalizationSummaries& localization,
                                   const std::vector<ReportTable>& tables) {
  ScalingSection section;
  if (!options.scaling) return section;
  section.points = MeasurePoints(options, plan, localization, tables);
  section.tables = Tables(options, section.points);
  section.csv = Csv(section.points);
  return section;
}

}  // namespace duskmap
