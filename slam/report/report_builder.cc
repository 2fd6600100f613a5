#include "slam/report/report_builder.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <set>
#include <sstream>

#include "slam/core/check.h"
#include "slam/io/output_safety.h"
#include "slam/report/report_cells.h"
#include "slam/report/report_table_ids.h"
#include "slam/report/scaling_tables.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

const char* kFullMerge = "1+2+3+4+5+6";
const char* kReduced = "1-2-3-4-5-6";

// Sums over the localization jobs of one table cell.
struct CellTotals {
  int frames = 0;
  int relocalized = 0;
  int no_candidate = 0;
  int correct = 0;
  int wrong = 0;
  std::array<int, 3> within = {0, 0, 0};  // per threshold: 0.25 m/2°, 0.5 m/5°, 5 m/10°
  bool has_ground_truth = false;
  double inliers_pct_sum = 0.0;  // weighted by re-localized frames
  double jump_mm_sum = 0.0;      // weighted by re-localized frames

  void Add(const LocalizationJobSummary& s) {
    frames += s.num_frames;
    relocalized += s.num_relocalized;
    no_candidate += s.num_no_candidate;
    correct += s.num_within_threshold[1];
    for (size_t i = 0; i < within.size(); ++i) within[i] += s.num_within_threshold[i];
    wrong += s.num_wrong;
    has_ground_truth = has_ground_truth || s.has_ground_truth;
    inliers_pct_sum += s.mean_inliers_pct * s.num_relocalized;
    jump_mm_sum += s.mean_jump_mm * s.num_relocalized;
  }
  double Pct(int count) const { return frames > 0 ? 100.0 * count / frames : 0.0; }
};

std::vector<std::string> MapRows(const ExperimentOptions& options, bool own_maps_only) {
  std::vector<std::string> rows;
  for (const MapSpec& map : options.maps) {
    if (!own_maps_only || map.BuildsItsOwnMap()) rows.push_back(map.label);
  }
  return rows;
}

bool HasRow(const ExperimentOptions& options, const std::string& label) {
  for (const MapSpec& map : options.maps) {
    if (map.label == label) return true;
  }
  return false;
}

void FillPaper(const std::optional<PaperReference>& paper, const std::string& table,
               const std::string& metric, ReportTable* out) {
  if (paper) paper->FillRows(table, metric, out);
}

// Every localization job together (each once: the closest-in-time row
// reuses the single maps' jobs), at the three thresholds: what the paper,
// without ground truth, could not report. None without ground truth.
std::optional<ReportTable> GroundTruthThresholdsTable(const ExperimentOptions& options,
                                                      const ExperimentPlan& plan,
                                                      const ExperimentResults& results) {
  std::map<std::string, CellTotals> by_feature;
  std::set<std::string> counted;
  for (const MatrixCell& cell : plan.cells) {
    const auto it = results.localization.find(cell.job_id);
    if (it == results.localization.end() || !counted.insert(cell.job_id).second) continue;
    by_feature[cell.feature].Add(it->second);
  }
  bool any_truth = false;
  for (const auto& [feature, t] : by_feature) any_truth = any_truth || t.has_ground_truth;
  if (!any_truth) return std::nullopt;
  const char* labels[3] = {"0.25 m/2°", "0.5 m/5°", "5 m/10°"};
  std::vector<std::string> threshold_rows;
  for (const char* label : labels) threshold_rows.push_back(std::string("correct within ") + label + " (%)");
  for (const char* label : labels) threshold_rows.push_back(std::string("wrong beyond ") + label + " (count)");
  ReportTable thresholds(kTableGroundTruthThresholds,
                         "Re-localizations against ground truth at three thresholds, every "
                         "localization job together",
                         threshold_rows, options.features, 1);
  for (const std::string& feature : options.features) {
    const auto found = by_feature.find(feature);
    if (found == by_feature.end() || found->second.frames == 0) continue;
    const CellTotals& f = found->second;
    for (size_t i = 0; i < 3; ++i) {
      thresholds.SetMeasured(threshold_rows[i], feature, f.Pct(f.within[i]));
      thresholds.SetMeasured(threshold_rows[3 + i], feature, f.relocalized - f.within[i]);
    }
  }
  return thresholds;
}

std::vector<ReportTable> RelocalizationTables(const ExperimentOptions& options,
                                              const ExperimentPlan& plan,
                                              const ExperimentResults& results,
                                              const std::optional<PaperReference>& paper) {
  const auto rows = MapRows(options, false);
  std::map<std::pair<std::string, std::string>, CellTotals> totals;  // (row, feature)
  for (const MatrixCell& cell : plan.cells) {
    const auto it = results.localization.find(cell.job_id);
    if (it != results.localization.end()) totals[{cell.row, cell.feature}].Add(it->second);
  }
  const std::string suffix = ", cumulative over the localization sessions";
  ReportTable relocalized(kTableRelocalizationPct, "Re-localization (% of frames)" + suffix, rows,
                          options.features);
  ReportTable inliers(kTableInliersPct,
                      "Visual inliers (% of features, re-localized frames)" + suffix, rows,
                      options.features);
  ReportTable jumps(kTableJumpsMm, "Average re-localization jump (mm)" + suffix, rows,
                    options.features);
  ReportTable correct(kTableCorrectPct,
                      "Correct re-localizations within 0.5 m/5° (% of frames)" + suffix, rows,
                      options.features);
  ReportTable wrong(kTableWrongCount, "Wrong re-localizations (count, beyond 0.5 m/5°)" + suffix,
                    rows, options.features);
  ReportTable no_candidate(kTableNoCandidatePct, "Frames with no candidate at all (%)" + suffix,
                           rows, options.features);
  for (const auto& [key, t] : totals) {
    const auto& [row, feature] = key;
    if (t.frames == 0) continue;
    relocalized.SetMeasured(row, feature, t.Pct(t.relocalized));
    no_candidate.SetMeasured(row, feature, t.Pct(t.no_candidate));
    if (t.relocalized > 0) {
      inliers.SetMeasured(row, feature, t.inliers_pct_sum / t.relocalized);
      jumps.SetMeasured(row, feature, t.jump_mm_sum / t.relocalized);
    }
    if (t.has_ground_truth) {
      correct.SetMeasured(row, feature, t.Pct(t.correct));
      wrong.SetMeasured(row, feature, t.wrong);
    }
  }
  const char* table = "table_cumulative_relocalization";
  FillPaper(paper, table, "relocalization_pct", &relocalized);
  FillPaper(paper, table, "visual_inliers_pct", &inliers);
  FillPaper(paper, table, "jumps_mm", &jumps);
  std::vector<ReportTable> tables = {relocalized, inliers, jumps, correct, wrong, no_candidate};
  if (auto thresholds = GroundTruthThresholdsTable(options, plan, results)) {
    tables.push_back(std::move(*thresholds));
  }
  return tables;
}

// The memory a localization job on this map recorded (what the localizer
// held), or the map job's estimate when no such job ran.
const std::map<std::string, size_t>* LocalizationMemory(const ExperimentPlan& plan,
                                                        const ExperimentResults& results,
                                                        const std::string& row,
                                                        const std::string& feature) {
  for (const MatrixCell& cell : plan.cells) {
    if (cell.row != row || cell.feature != feature) continue;
    const auto it = results.localization.find(cell.job_id);
    if (it != results.localization.end() && !it->second.memory_bytes.empty()) {
      return &it->second.memory_bytes;
    }
  }
  const auto map = results.maps.find("map/" + feature + "/" + row);
  return map == results.maps.end() ? nullptr : &map->second.memory_bytes;
}

std::vector<ReportTable> MapTables(const ExperimentOptions& options, const ExperimentPlan& plan,
                                   const ExperimentResults& results,
                                   const std::optional<PaperReference>& paper) {
  const auto rows = MapRows(options, true);
  ReportTable nodes(kTableGraphNodes, "Graph size (nodes)", rows, options.features);
  ReportTable memory(kTableMemoryMb, "Memory needed for localization (MB)", rows, options.features,
                     1);
  ReportTable per_node(kTableMemoryPerNodeKib,
                       "Memory needed for localization per node (KiB); the paper's: RAM (its "
                       "constant overhead excluded) / nodes",
                       rows, options.features, 1);
  std::vector<std::string> ate_rows;
  for (const std::string& row : rows) {
    if (ParseMapSpec(row).kind != MapKind::kSingle) ate_rows.push_back(row);
  }
  ReportTable ate(kTableAteMm, "ATE of the merged maps against ground truth (mm)", ate_rows,
                  options.features);
  for (const std::string& feature : options.features) {
    for (const std::string& row : rows) {
      const auto it = results.maps.find("map/" + feature + "/" + row);
      if (it == results.maps.end()) continue;
      const MapJobSummary& s = it->second;
      nodes.SetMeasured(row, feature, s.num_nodes);
      size_t bytes = 0;
      for (const auto& [component, component_bytes] : *LocalizationMemory(plan, results, row, feature)) {
        bytes += component_bytes;
      }
      memory.SetMeasured(row, feature, bytes / (1024.0 * 1024.0));
      if (s.num_nodes > 0) per_node.SetMeasured(row, feature, bytes / 1024.0 / s.num_nodes);
      if (s.ate_mm >= 0.0 && ParseMapSpec(row).kind != MapKind::kSingle) {
        ate.SetMeasured(row, feature, s.ate_mm);
      }
    }
  }
  FillPaper(paper, "table_ram_mb", "nodes", &nodes);
  FillPaper(paper, "table_ram_mb", "ram_mb", &memory);
  FillPaper(paper, "table_ate_mm", "", &ate);
  if (paper) {
    for (const std::string& row : rows) {
      for (const std::string& feature : options.features) {
        const auto ram = paper->Value({"table_ram_mb", "ram_mb", row}, feature);
        const auto paper_nodes = paper->Value({"table_ram_mb", "nodes", row}, feature);
        if (ram && paper_nodes && *paper_nodes > 0) {
          per_node.SetPaper(row, feature, *ram * 1024.0 / *paper_nodes);
        }
      }
    }
  }
  std::vector<ReportTable> tables = {nodes, memory, per_node, ate};

  if (HasRow(options, kReduced) && HasRow(options, kFullMerge)) {
    ReportTable reduced(kTableGraphReduction,
                        "Graph reduction: nodes left in 1-2-3-4-5-6 and reduction (%)",
                        {"nodes", "reduction_pct"}, options.features);
    for (const std::string& feature : options.features) {
      const auto r = results.maps.find("map/" + feature + "/" + kReduced);
      const auto f = results.maps.find("map/" + feature + "/" + kFullMerge);
      if (r == results.maps.end() || f == results.maps.end() || f->second.num_nodes == 0) continue;
      reduced.SetMeasured("nodes", feature, r->second.num_nodes);
      reduced.SetMeasured("reduction_pct", feature,
                          100.0 * (1.0 - double(r->second.num_nodes) / f->second.num_nodes));
    }
    FillPaper(paper, "table_reduced_graph", "", &reduced);
    tables.push_back(reduced);
  }
  return tables;
}

// One feature's column of the timing table, as measured.
struct FeatureTimings {
  // Over the feature's localization jobs (each job once).
  OptionalMean detection, te, features, lcd_single, lcd_full, lcd_reduced, lcd_te_full;
  // Over its maps.
  OptionalMean vocab_single, map_single_s;
  std::optional<double> vocab_full, vocab_reduced, descriptor_bytes;
};

FeatureTimings MeasureTimings(const std::string& feature, const ExperimentPlan& plan,
                              const ExperimentResults& results) {
  FeatureTimings t;
  std::set<std::string> seen;
  for (const MatrixCell& cell : plan.cells) {
    if (cell.feature != feature || !seen.insert(cell.job_id).second) continue;
    const auto it = results.localization.find(cell.job_id);
    if (it == results.localization.end()) continue;
    const LocalizationJobSummary& s = it->second;
    t.detection.Add(s.mean_times_ms.features);
    t.te.Add(s.mean_times_ms.transformation_estimation);
    t.features.Add(s.mean_features);
    const MapSpec used = plan.FindJob(cell.job_id)->map;
    const double lcd = s.mean_times_ms.loop_closure_detection;
    if (used.kind == MapKind::kSingle) t.lcd_single.Add(lcd);
    if (used.label == kFullMerge) {
      t.lcd_full.Add(lcd);
      t.lcd_te_full.Add(s.median_lcd_te_ms);
    }
    if (used.label == kReduced) t.lcd_reduced.Add(lcd);
  }
  for (const auto& [id, s] : results.maps) {
    const Job* job = plan.FindJob(id);
    if (job == nullptr || job->feature != feature) continue;
    if (job->map.kind == MapKind::kSingle) {
      t.vocab_single.Add(s.vocabulary_words / 1000.0);
      t.map_single_s.Add(s.build_wall_s);
    }
    if (job->map.label == kFullMerge) t.vocab_full = s.vocabulary_words / 1000.0;
    if (job->map.label == kReduced) t.vocab_reduced = s.vocabulary_words / 1000.0;
    t.descriptor_bytes = static_cast<double>(s.descriptor_bytes_per_feature);
  }
  return t;
}

void SetTimingPaper(const PaperReference& paper, const std::vector<std::string>& rows,
                    const std::string& feature, ReportTable* table) {
  const std::string t = "table_timing";
  const std::vector<std::pair<std::string, std::vector<std::string>>> paper_keys = {
      {rows[0], {t, "feature_detection_ms"}},
      {rows[1], {t, "loop_closure_detection_ms", "single-session maps"}},
      {rows[2], {t, "loop_closure_detection_ms", kFullMerge}},
      {rows[3], {t, "loop_closure_detection_ms", kReduced}},
      {rows[4], {t, "transformation_estimation_ms"}},
      {rows[5], {t, "features_per_frame"}},
      {rows[6], {t, "vocabulary_size_thousands", "single-session maps"}},
      {rows[7], {t, "vocabulary_size_thousands", kFullMerge}},
      {rows[8], {t, "vocabulary_size_thousands", kReduced}}};
  for (const auto& [row, keys] : paper_keys) {
    if (const auto value = paper.Value(keys, feature)) table->SetPaper(row, feature, *value);
  }
  const auto dims = paper.Value({t, "descriptor_dimension"}, feature);
  const auto element = paper.Value({t, "descriptor_bytes_per_element"}, feature);
  if (dims && element) table->SetPaper(rows[9], feature, *dims * *element);
}

ReportTable TimingTable(const ExperimentOptions& options, const ExperimentPlan& plan,
                        const ExperimentResults& results,
                        const std::optional<PaperReference>& paper) {
  const std::vector<std::string> rows = {kRowFeatureDetectionMs,
                                         kRowLcdSingleSessionMs,
                                         kRowLcdFullMergeMs,
                                         "lcd_1-2-3-4-5-6_ms",
                                         kRowTeMs,
                                         kRowFeaturesPerFrame,
                                         "vocabulary_single_session_k",
                                         "vocabulary_1+2+3+4+5+6_k",
                                         "vocabulary_1-2-3-4-5-6_k",
                                         "descriptor_bytes",
                                         "lcd_te_median_1+2+3+4+5+6_ms",
                                         "map_single_session_s"};
  ReportTable table(kTableTiming,
                    "Per-frame timings (localization, ms), features per frame, vocabulary "
                    "(thousands of words), descriptor size (bytes), median LCD + TE per frame on "
                    "the six-session map (ms) and single-session map building from cached "
                    "features (s, wall)",
                    rows, options.features, 1);
  for (const std::string& feature : options.features) {
    const FeatureTimings m = MeasureTimings(feature, plan, results);
    const std::vector<std::pair<std::string, std::optional<double>>> values = {
        {rows[0], m.detection.Get()},   {rows[1], m.lcd_single.Get()}, {rows[2], m.lcd_full.Get()},
        {rows[3], m.lcd_reduced.Get()}, {rows[4], m.te.Get()},         {rows[5], m.features.Get()},
        {rows[6], m.vocab_single.Get()}, {rows[7], m.vocab_full},      {rows[8], m.vocab_reduced},
        {rows[9], m.descriptor_bytes}, {rows[10], m.lcd_te_full.Get()}, {rows[11], m.map_single_s.Get()}};
    for (const auto& [row, value] : values) {
      if (value) table.SetMeasured(row, feature, *value);
    }
    if (paper) SetTimingPaper(*paper, rows, feature, &table);
  }
  return table;
}

// One consecutive pair's line of consecutive.csv.
void WriteConsecutiveCsvLine(const ConsecutiveCell& cell, const LocalizationJobSummary& s,
                             std::ostream& out) {
  out << cell.feature << "," << cell.map_session << "," << cell.localization_session << ","
      << cell.gap_min << "," << cell.gap_class_min << "," << s.max_gap_m << ","
      << 100.0 * s.num_within_55cm / s.num_frames << ","
      << 100.0 * s.num_relocalized / s.num_frames << ",";
  if (s.num_within_55cm_bound >= 0) out << 100.0 * s.num_within_55cm_bound / s.num_frames;
  out << "\n";
}

// The paper's gap-distance table beside the largest gap and the share
// within 55 cm, per gap class (the tables' rows) and feature.
void FillGapDistancePaper(const PaperReference& paper, ReportTable* max_gap,
                          ReportTable* within) {
  for (const std::string& row : max_gap->rows()) {
    for (const std::string& feature : max_gap->columns()) {
      if (auto v = paper.Value({"table_gap_distance", row, "max_gap_m"}, feature)) {
        max_gap->SetPaper(row, feature, *v);
      }
      if (auto v = paper.Value({"table_gap_distance", row, "within_55cm_pct"}, feature)) {
        within->SetPaper(row, feature, *v);
      }
    }
  }
}

std::vector<ReportTable> ConsecutiveTables(const ExperimentOptions& options,
                                           const ExperimentPlan& plan,
                                           const ExperimentResults& results,
                                           const std::optional<PaperReference>& paper,
                                           std::string* csv) {
  if (plan.consecutive.empty()) return {};
  std::vector<std::string> rows;
  for (int gap : options.consecutive_gap_classes_min) rows.push_back(std::to_string(gap) + " min");
  ReportTable max_gap(kTableConsecutiveMaxGapM,
                      "Consecutive sessions: largest distance travelled without "
                      "re-localization (m), worst pair of each gap class",
                      rows, options.features, 2);
  ReportTable within(kTableConsecutiveWithin55cmPct,
                     "Consecutive sessions: frames re-localized within 55 cm of the previous "
                     "re-localization (%)",
                     rows, options.features);
  ReportTable bound(kTableConsecutiveWithin55cmBoundPct,
                    "Consecutive sessions: the most frames the 55-cm rule can count on these "
                    "paths, every frame re-localized (%): a frame more than 55 cm after the one "
                    "before never counts",
                    rows, options.features);
  struct ClassSums {
    double max_gap_m = 0.0;
    int within = 0;
    int bound = 0;
    bool bound_known = true;  // every summary of the class recorded its bound
    int frames = 0;
  };
  std::map<std::pair<std::string, std::string>, ClassSums> acc;
  std::ostringstream out;
  out << "feature,map_session,localization_session,gap_min,gap_class_min,max_gap_m,"
         "within_55cm_pct,relocalized_pct,within_55cm_bound_pct\n";
  for (const ConsecutiveCell& cell : plan.consecutive) {
    const auto it = results.localization.find(cell.job_id);
    if (it == results.localization.end() || it->second.num_frames == 0) continue;
    const LocalizationJobSummary& s = it->second;
    ClassSums& a = acc[{std::to_string(cell.gap_class_min) + " min", cell.feature}];
    a.max_gap_m = std::max(a.max_gap_m, s.max_gap_m);
    a.within += s.num_within_55cm;
    a.frames += s.num_frames;
    if (s.num_within_55cm_bound >= 0) {
      a.bound += s.num_within_55cm_bound;
    } else {
      a.bound_known = false;
    }
    WriteConsecutiveCsvLine(cell, s, out);
  }
  for (const auto& [key, a] : acc) {
    max_gap.SetMeasured(key.first, key.second, a.max_gap_m);
    within.SetMeasured(key.first, key.second, 100.0 * a.within / a.frames);
    if (a.bound_known) bound.SetMeasured(key.first, key.second, 100.0 * a.bound / a.frames);
  }
  if (paper) FillGapDistancePaper(*paper, &max_gap, &within);
  *csv = out.str();
  return {max_gap, within, bound};
}

SingleMapMatrix BuildSingleMapMatrix(const ExperimentOptions& options, const ExperimentPlan& plan,
                                     const ExperimentResults& results) {
  SingleMapMatrix matrix;
  std::string closest_label;
  for (const MapSpec& map : options.maps) {
    if (map.kind == MapKind::kSingle) matrix.map_rows.push_back(map.label);
    if (map.kind == MapKind::kClosestInTime) closest_label = map.label;
  }
  matrix.sessions = options.localization_sessions;
  matrix.closest_row.assign(matrix.sessions.size(), "");
  const auto index = [](const std::vector<std::string>& list, const std::string& value) {
    return static_cast<size_t>(std::find(list.begin(), list.end(), value) - list.begin());
  };
  for (const MatrixCell& cell : plan.cells) {
    const size_t s = index(matrix.sessions, cell.session);
    if (s >= matrix.sessions.size()) continue;
    if (!closest_label.empty() && cell.row == closest_label) {
      if (const Job* job = plan.FindJob(cell.job_id)) matrix.closest_row[s] = job->map.label;
      continue;
    }
    const size_t r = index(matrix.map_rows, cell.row);
    const auto it = results.localization.find(cell.job_id);
    if (r >= matrix.map_rows.size() || it == results.localization.end() ||
        it->second.num_frames == 0) {
      continue;
    }
    auto& pct = matrix.pct[cell.feature];
    if (pct.empty()) {
      pct.assign(matrix.map_rows.size(),
                 std::vector<std::optional<double>>(matrix.sessions.size()));
    }
    pct[r][s] = 100.0 * it->second.num_relocalized / it->second.num_frames;
  }
  return matrix;
}

std::string CellsCsv(const ExperimentPlan& plan, const ExperimentResults& results) {
  std::ostringstream out;
  out << "feature,row,session,job,frames,relocalized_pct,correct_pct,wrong,no_candidate_pct,"
         "mean_inliers_pct,mean_jump_mm,correct_0.25m_2deg_pct,correct_5m_10deg_pct\n";
  for (const MatrixCell& cell : plan.cells) {
    const auto it = results.localization.find(cell.job_id);
    if (it == results.localization.end() || it->second.num_frames == 0) continue;
    const LocalizationJobSummary& s = it->second;
    const double frames = s.num_frames;
    out << cell.feature << ",\"" << cell.row << "\"," << cell.session << "," << cell.job_id << ","
        << s.num_frames << "," << 100.0 * s.num_relocalized / frames << ","
        << (s.has_ground_truth ? 100.0 * s.num_within_threshold[1] / frames : -1.0) << ","
        << s.num_wrong << "," << 100.0 * s.num_no_candidate / frames << "," << s.mean_inliers_pct
        << "," << s.mean_jump_mm << ","
        << (s.has_ground_truth ? 100.0 * s.num_within_threshold[0] / frames : -1.0) << ","
        << (s.has_ground_truth ? 100.0 * s.num_within_threshold[2] / frames : -1.0) << "\n";
  }
  return out.str();
}

std::string TimelineCsv(const ExperimentResults& results) {
  std::ostringstream out;
  out << "job,frame,matched_session\n";
  for (const auto& [id, s] : results.localization) {
    for (size_t i = 0; i < s.matched_session_per_frame.size(); ++i) {
      out << id << "," << i << "," << s.matched_session_per_frame[i] << "\n";
    }
  }
  return out.str();
}

std::string FileStem(const std::string& caption) {
  std::string stem;
  for (char c : caption) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      stem += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!stem.empty() && stem.back() != '_') {
      stem += '_';
    }
    if (stem.size() >= 48) break;
  }
  while (!stem.empty() && stem.back() == '_') stem.pop_back();
  return stem;
}

void WriteText(const fs::path& path, const std::string& text) {
  WriteFileAtomically(path.string(), [&](std::ostream& out) { out << text; });
}

}  // namespace

ExperimentResults CollectResults(const ExperimentPlan& plan,
                                 const std::vector<fs::path>& results_dirs) {
  ExperimentResults results;
  for (const Job& job : plan.jobs) {
    if (job.kind == JobKind::kExtract) continue;
    bool found = false;
    for (const fs::path& dir : results_dirs) {
      const fs::path job_dir = dir / "jobs" / job.id;
      if (!fs::is_directory(job_dir)) continue;
      if (job.kind == JobKind::kLocalize) {
        results.localization[job.id] = ReadLocalizationJobSummary(job_dir);
      } else {
        results.maps[job.id] = ReadMapJobSummary(job_dir);
      }
      found = true;
      break;
    }
    if (!found) results.missing_jobs.push_back(job.id);
  }
  return results;
}

// Where a localization job's time goes before and besides its frames: map
// loads (jobs on a map share one loaded copy), the localizer's construction
// with its vocabulary index (restored from the map, or rebuilt), and the
// frames' own work; and the index each map stores, built once at mapping.
ReportTable TimingBudgetTable(const ExperimentOptions& options, const ExperimentResults& results,
                              const ExperimentPlan& plan) {
  const std::vector<std::string> rows = {
      "localization_jobs",      "map_loads",          "map_load_s",
      "map_load_1+2+3+4+5+6_s", "localizer_setup_s",  "index_restore_s",
      "index_restore_1+2+3+4+5+6_s", "index_rebuilt_jobs", "frames_s",
      "index_build_at_mapping_s", "index_build_1+2+3+4+5+6_s"};
  ReportTable table(kTableTimingBudget,
                    "Timing budget of the localization jobs (s, wall; per job unless counted): "
                    "map loads (one per map and worker, the other jobs share it), localizer "
                    "setup with the vocabulary index restored from the map (or rebuilt), the "
                    "frames' work from cached features, and the index built once per map at "
                    "mapping",
                    rows, options.features, 2);
  for (const std::string& feature : options.features) {
    OptionalMean load, load_full, setup, restore, restore_full, frames, build, build_full;
    int jobs = 0, loads = 0, rebuilt = 0;
    for (const auto& [id, s] : results.localization) {
      const Job* job = plan.FindJob(id);
      if (job == nullptr || job->feature != feature) continue;
      ++jobs;
      const bool full = job->map.label == kFullMerge;
      if (!s.map_from_cache) {
        ++loads;
        load.Add(s.map_load_s);
        if (full) load_full.Add(s.map_load_s);
      }
      setup.Add(s.localizer_setup_s);
      restore.Add(s.index_restore_s);
      if (full) restore_full.Add(s.index_restore_s);
      if (!s.index_restored && !s.index_rebuild_reason.empty()) ++rebuilt;
      // Per-frame stages without extraction (the features come from the cache).
      frames.Add(s.num_frames * (s.mean_times_ms.total - s.mean_times_ms.features) / 1000.0);
    }
    for (const auto& [id, s] : results.maps) {
      const Job* job = plan.FindJob(id);
      if (job == nullptr || job->feature != feature) continue;
      build.Add(s.index_build_s);
      if (job->map.label == kFullMerge) build_full.Add(s.index_build_s);
    }
    if (jobs == 0) continue;
    const std::vector<std::pair<std::string, std::optional<double>>> values = {
        {rows[0], jobs},           {rows[1], loads},          {rows[2], load.Get()},
        {rows[3], load_full.Get()}, {rows[4], setup.Get()},   {rows[5], restore.Get()},
        {rows[6], restore_full.Get()}, {rows[7], rebuilt},    {rows[8], frames.Get()},
        {rows[9], build.Get()},    {rows[10], build_full.Get()}};
    for (const auto& [row, value] : values) {
      if (value) table.SetMeasured(row, feature, *value);
    }
  }
  return table;
}

ExperimentReport BuildReport(const ExperimentOptions& options, const ExperimentPlan& plan,
                             const ExperimentResults& results,
                             const std::optional<PaperReference>& paper) {
  ExperimentReport report;
  if (!options.maps.empty()) {
    for (auto& t : RelocalizationTables(options, plan, results, paper)) report.tables.push_back(t);
    for (auto& t : MapTables(options, plan, results, paper)) report.tables.push_back(t);
    report.tables.push_back(TimingTable(options, plan, results, paper));
    report.tables.push_back(TimingBudgetTable(options, results, plan));
  }
  for (auto& t : ConsecutiveTables(options, plan, results, paper, &report.consecutive_csv)) {
    report.tables.push_back(t);
  }
  ScalingSection scaling = BuildScalingSection(options, plan, results.localization, report.tables);
  for (auto& t : scaling.tables) report.tables.push_back(std::move(t));
  report.scaling_csv = std::move(scaling.csv);
  report.cells_csv = CellsCsv(plan, results);
  report.timeline_csv = TimelineCsv(results);
  report.single_maps = BuildSingleMapMatrix(options, plan, results);
  if (paper) report.agreement = ComputeAgreement(report.tables, report.single_maps, *paper);
  return report;
}

void WriteReport(const ExperimentReport& report, const fs::path& dir) {
  std::error_code error;
  fs::create_directories(dir / "tables", error);
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(dir / "tables"))
      << dir.string() << ": cannot create the report folder";
  std::ostringstream markdown;
  std::ostringstream latex;
  for (const ReportTable& table : report.tables) {
    markdown << table.ToMarkdown() << "\n";
    latex << table.ToLatex() << "\n";
    WriteText(dir / "tables" / (FileStem(table.caption()) + ".csv"), table.ToCsv());
  }
  WriteText(dir / "tables.md", markdown.str());
  WriteText(dir / "tables.tex", latex.str());
  WriteText(dir / "cells.csv", report.cells_csv);
  WriteText(dir / "timeline.csv", report.timeline_csv);
  if (!report.consecutive_csv.empty()) WriteText(dir / "consecutive.csv", report.consecutive_csv);
  if (!report.scaling_csv.empty()) {
    WriteText(dir / "scaling.csv", report.scaling_csv);
  } else {
    fs::remove(dir / "scaling.csv", error);  // an earlier report's curve
  }
  if (report.agreement) {
    WriteText(dir / "agreement.md", AgreementToMarkdown(*report.agreement));
    WriteText(dir / "agreement.json", AgreementToJson(*report.agreement).dump(2) + "\n");
  } else {
    // An earlier report's agreement would describe other tables.
    fs::remove(dir / "agreement.md", error);
    fs::remove(dir / "agreement.json", error);
  }
}

}  // namespace duskmap
