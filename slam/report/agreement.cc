#include "slam/report/agreement.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <sstream>

#include "slam/report/report_cells.h"
#include "slam/report/report_table_ids.h"

namespace duskmap {
namespace {

TableDeviation Deviation(const std::string& name, const std::string& unit, AgreementRole role,
                         const ReportTable* table,
                         const std::function<bool(const std::string&)>& row_filter, int decimals) {
  TableDeviation deviation;
  deviation.name = name;
  deviation.unit = unit;
  deviation.role = role;
  if (table == nullptr) return deviation;
  double sum = 0.0;
  for (const std::string& row : table->rows()) {
    if (!row_filter(row)) continue;
    for (const std::string& column : table->columns()) {
      const TableCell& cell = table->At(row, column);
      if (!cell.measured || !cell.paper) continue;
      const double difference = std::abs(*cell.measured - *cell.paper);
      sum += difference;
      ++deviation.cells;
      if (!deviation.max_abs_deviation || difference > *deviation.max_abs_deviation) {
        deviation.max_abs_deviation = difference;
        deviation.worst_cell = column + " on " + row + ": " +
                               FormatFixed(*cell.measured, decimals) + " (paper " +
                               FormatFixed(*cell.paper, decimals) + ")";
      }
    }
  }
  if (deviation.cells > 0) deviation.mean_abs_deviation = sum / deviation.cells;
  return deviation;
}

std::vector<double> AverageRanks(const std::vector<double>& values) {
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(values.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && values[order[j + 1]] == values[order[i]]) ++j;
    const double rank = 0.5 * (i + j) + 1.0;
    for (size_t k = i; k <= j; ++k) ranks[order[k]] = rank;
    i = j + 1;
  }
  return ranks;
}

// The mean over `rows` of a feature's cells on one side; nullopt when any is missing.
RankAgreement Ranking(const ReportTable* relocalization) {
  RankAgreement ranking;
  const std::vector<std::string> rows = SingleSessionRows(relocalization);
  for (const std::string& feature : PaperColumns(relocalization)) {
    const auto measured = RowMean(relocalization, rows, feature, TableSide::kMeasured);
    const auto paper = RowMean(relocalization, rows, feature, TableSide::kPaper);
    if (!measured || !paper) continue;
    ranking.features.push_back(feature);
    ranking.measured_mean_pct.push_back(*measured);
    ranking.paper_mean_pct.push_back(*paper);
  }
  ranking.spearman_rho = SpearmanRho(ranking.measured_mean_pct, ranking.paper_mean_pct);
  const auto range = SpearmanRhoRange(ranking.measured_mean_pct, ranking.paper_mean_pct,
                                      kRankResolutionPts);
  if (range) {
    ranking.spearman_rho_low = range->first;
    ranking.spearman_rho_high = range->second;
  }
  const std::vector<double>& m = ranking.measured_mean_pct;
  for (size_t i = 0; i < m.size(); ++i) {
    for (size_t j = i + 1; j < m.size(); ++j) {
      const double gap = std::abs(m[i] - m[j]);
      if (gap >= kRankResolutionPts) continue;
      const bool i_higher = m[i] >= m[j];
      ranking.close_pairs.push_back({ranking.features[i_higher ? i : j],
                                     ranking.features[i_higher ? j : i], gap});
    }
  }
  return ranking;
}

NightMinusDay NightDay(const ReportTable* relocalization, const RankAgreement& ranking) {
  NightMinusDay result;
  const std::vector<std::string> rows = SingleSessionRows(relocalization);
  if (rows.size() < 2 || ranking.features.empty()) return result;
  result.day_row = rows.front();
  result.night_row = rows.back();
  for (TableSide side : {TableSide::kMeasured, TableSide::kPaper}) {
    double sum = 0.0;
    int count = 0;
    for (const std::string& feature : ranking.features) {
      const auto night = CellValue(relocalization, result.night_row, feature, side);
      const auto day = CellValue(relocalization, result.day_row, feature, side);
      if (!night || !day) continue;
      sum += *night - *day;
      ++count;
    }
    if (count == 0) continue;
    (side == TableSide::kMeasured ? result.measured_pts : result.paper_pts) = sum / count;
  }
  return result;
}

std::vector<RowSignedDeviation> SingleMapRows(const ReportTable* relocalization, const RankAgreement& ranking) {
  std::vector<RowSignedDeviation> rows;
  for (const std::string& row : SingleSessionRows(relocalization)) {
    RowSignedDeviation deviation;
    deviation.row = row;
    double sum = 0.0;
    for (const std::string& feature : ranking.features) {
      const auto measured = CellValue(relocalization, row, feature, TableSide::kMeasured);
      const auto paper = CellValue(relocalization, row, feature, TableSide::kPaper);
      if (!measured || !paper) continue;
      sum += *measured - *paper;
      ++deviation.features;
    }
    if (deviation.features > 0) deviation.mean_pts = sum / deviation.features;
    rows.push_back(deviation);
  }
  return rows;
}

std::vector<FeatureRatio> FeatureRatios(const ReportTable* timing) {
  std::vector<FeatureRatio> ratios;
  if (timing == nullptr || !timing->HasRow(kRowFeaturesPerFrame)) return ratios;
  for (const std::string& feature : timing->columns()) {
    const TableCell& cell = timing->At(kRowFeaturesPerFrame, feature);
    if (!cell.measured || !cell.paper || *cell.paper <= 0.0) continue;
    ratios.push_back({feature, *cell.measured, *cell.paper, *cell.measured / *cell.paper});
  }
  return ratios;
}

std::string OptionalNumber(const std::optional<double>& value, int decimals) {
  return value ? FormatFixed(*value, decimals) : "–";
}

// Text for a Markdown table cell: '|' (as in the map label 1|2|3) escaped.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

nlohmann::json OptionalJson(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::vector<ConsecutiveBound> ConsecutiveBounds(const ReportTable* within,
                                               const ReportTable* bound) {
  std::vector<ConsecutiveBound> bounds;
  if (within == nullptr || bound == nullptr) return bounds;
  for (const std::string& row : within->rows()) {
    if (!bound->HasRow(row)) continue;
    ConsecutiveBound b;
    b.row = row;
    for (const std::string& feature : within->columns()) {
      if (!bound->HasColumn(feature)) continue;
      const TableCell& w = within->At(row, feature);
      const TableCell& most = bound->At(row, feature);
      if (!w.measured || !most.measured) continue;
      b.features.push_back(feature);
      b.measured_pct.push_back(*w.measured);
      b.bound_pct.push_back(*most.measured);
      b.paper_pct.push_back(w.paper);
    }
    if (!b.features.empty()) bounds.push_back(std::move(b));
  }
  return bounds;
}

}  // namespace

const char* AgreementRoleName(AgreementRole role) {
  return role == AgreementRole::kCalibration ? "calibration" : "held out";
}

int AgreementReport::FindingsReproduced() const {
  return static_cast<int>(std::count_if(
      findings.begin(), findings.end(),
      [](const FindingCheck& f) { return f.verdict == FindingVerdict::kReproduced; }));
}

int AgreementReport::FindingsDecided() const {
  return static_cast<int>(std::count_if(
      findings.begin(), findings.end(),
      [](const FindingCheck& f) { return f.verdict != FindingVerdict::kNotDecided; }));
}

const TableDeviation* AgreementReport::FindDeviation(const std::string& name) const {
  for (const TableDeviation& deviation : deviations) {
    if (deviation.name == name) return &deviation;
  }
  return nullptr;
}

std::optional<double> SpearmanRho(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || a.size() < 3) return std::nullopt;
  const std::vector<double> ra = AverageRanks(a);
  const std::vector<double> rb = AverageRanks(b);
  const double n = static_cast<double>(a.size());
  const double mean = (n + 1.0) / 2.0;
  double covariance = 0.0, variance_a = 0.0, variance_b = 0.0;
  for (size_t i = 0; i < ra.size(); ++i) {
    covariance += (ra[i] - mean) * (rb[i] - mean);
    variance_a += (ra[i] - mean) * (ra[i] - mean);
    variance_b += (rb[i] - mean) * (rb[i] - mean);
  }
  if (variance_a <= 0.0 || variance_b <= 0.0) return std::nullopt;
  return covariance / std::sqrt(variance_a * variance_b);
}

std::optional<std::pair<double, double>> SpearmanRhoRange(const std::vector<double>& measured,
                                                          const std::vector<double>& reference,
                                                          double resolution) {
  if (!SpearmanRho(measured, reference) || measured.size() > kMaxFeaturesForRhoRange) {
    return std::nullopt;
  }
  const size_t n = measured.size();
  std::vector<size_t> order(n);  // order[k]: the value ranked k-th from the top
  std::iota(order.begin(), order.end(), 0);
  std::optional<std::pair<double, double>> range;
  std::vector<double> scores(n);
  do {
    // An order may not put a value below one it exceeds by `resolution` or more.
    bool allowed = true;
    for (size_t above = 0; above < n && allowed; ++above) {
      for (size_t below = above + 1; below < n; ++below) {
        if (measured[order[below]] - measured[order[above]] >= resolution) {
          allowed = false;
          break;
        }
      }
    }
    if (!allowed) continue;
    for (size_t k = 0; k < n; ++k) scores[order[k]] = static_cast<double>(n - k);
    const double rho = *SpearmanRho(scores, reference);
    if (!range) {
      range = std::make_pair(rho, rho);
    } else {
      range->first = std::min(range->first, rho);
      range->second = std::max(range->second, rho);
    }
  } while (std::next_permutation(order.begin(), order.end()));
  return range;
}

AgreementReport ComputeAgreement(const std::vector<ReportTable>& tables,
                                 const SingleMapMatrix& single_maps, const PaperReference& paper) {
  const ReportTable* relocalization = FindTable(tables, kTableRelocalizationPct);
  const ReportTable* max_gap = FindTable(tables, kTableConsecutiveMaxGapM);
  AgreementReport agreement;
  const auto all = [](const std::string&) { return true; };
  agreement.deviations.push_back(Deviation(kDeviationSingleMaps, "points",
                                           AgreementRole::kCalibration, relocalization,
                                           IsSingleSessionRow, 0));
  agreement.deviations.push_back(Deviation(
      kDeviationMultiMaps, "points", AgreementRole::kHeldOut, relocalization,
      [](const std::string& row) { return !IsSingleSessionRow(row); }, 0));
  agreement.deviations.push_back(Deviation(kDeviationInliers, "points", AgreementRole::kHeldOut,
                                           FindTable(tables, kTableInliersPct), all, 0));
  agreement.deviations.push_back(Deviation(kDeviationJumps, "mm", AgreementRole::kHeldOut,
                                           FindTable(tables, kTableJumpsMm), all, 0));
  const ReportTable* within = FindTable(tables, kTableConsecutiveWithin55cmPct);
  if (within != nullptr) {
    for (const std::string& row : within->rows()) {
      agreement.deviations.push_back(Deviation(
          "consecutive " + row + ": within 55 cm", "points", AgreementRole::kHeldOut, within,
          [&](const std::string& r) { return r == row; }, 0));
    }
  }
  if (max_gap != nullptr) {
    for (const std::string& row : max_gap->rows()) {
      agreement.deviations.push_back(Deviation(
          "consecutive " + row + ": largest gap", "m", AgreementRole::kHeldOut, max_gap,
          [&](const std::string& r) { return r == row; }, 2));
    }
  }
  agreement.ranking = Ranking(relocalization);
  agreement.night_minus_day = NightDay(relocalization, agreement.ranking);
  agreement.single_map_rows = SingleMapRows(relocalization, agreement.ranking);
  agreement.features_per_frame = FeatureRatios(FindTable(tables, kTableTiming));
  agreement.consecutive_bounds =
      ConsecutiveBounds(within, FindTable(tables, kTableConsecutiveWithin55cmBoundPct));
  agreement.findings = CheckPaperFindings(tables, single_maps, paper.Findings());
  return agreement;
}

namespace {

void DeviationsMarkdown(const AgreementReport& agreement, std::ostream& out) {
  out << "**Mean absolute deviation from the paper** (cells with both values; calibration = "
         "what the synthetic dataset may be tuned on, held out = never tuned on)\n\n"
      << "| table | unit | cells | mean abs. deviation | largest (cell) | role |\n"
      << "| --- | --- | ---: | ---: | --- | --- |\n";
  for (const TableDeviation& d : agreement.deviations) {
    const int decimals = d.unit == "m" ? 2 : 1;
    out << "| " << Cell(d.name) << " | " << d.unit << " | " << d.cells << " | "
        << OptionalNumber(d.mean_abs_deviation, decimals) << " | "
        << (d.max_abs_deviation
                ? FormatFixed(*d.max_abs_deviation, decimals) + " (" + Cell(d.worst_cell) + ")"
                : "–")
        << " | " << AgreementRoleName(d.role) << " |\n";
  }
}

void RankingMarkdown(const RankAgreement& r, std::ostream& out) {
  out << "\n**Features ranked by mean single-session-map re-localization**: Spearman ρ = "
      << OptionalNumber(r.spearman_rho, 2) << " over " << r.features.size() << " features";
  if (!r.features.empty()) {
    out << " (measured / paper, %:";
    for (size_t i = 0; i < r.features.size(); ++i) {
      out << " " << r.features[i] << " " << FormatFixed(r.measured_mean_pct[i], 1) << "/"
          << FormatFixed(r.paper_mean_pct[i], 1);
    }
    out << ")";
  }
  if (!r.close_pairs.empty() && r.spearman_rho_low && r.spearman_rho_high) {
    out << "; within " << FormatFixed(kRankResolutionPts, 1)
        << " points of each other, an order one run does not decide:";
    for (const ClosePair& pair : r.close_pairs) {
      out << " " << pair.higher << "/" << pair.lower << " " << FormatFixed(pair.gap_pts, 1);
    }
    out << "; ρ over the orders they allow " << FormatFixed(*r.spearman_rho_low, 2) << " to "
        << FormatFixed(*r.spearman_rho_high, 2);
  }
  out << "\n\n";
}

// Night minus day, the signed deviation per single-session map and the
// features per frame: one paragraph each, when the report has it.
void MapAndFeatureMarkdown(const AgreementReport& agreement, std::ostream& out) {
  const NightMinusDay& n = agreement.night_minus_day;
  if (!n.night_row.empty()) {
    out << "**Night map minus day map** (map " << n.night_row << " − map " << n.day_row
        << ", cumulative re-localization, mean over the ranked features): "
        << (n.measured_pts ? FormatSigned(*n.measured_pts, 1) : "–") << " points (paper "
        << (n.paper_pts ? FormatSigned(*n.paper_pts, 1) : "–") << ")\n\n";
  }
  if (!agreement.single_map_rows.empty()) {
    out << "**Single-session maps, signed deviation per map** (measured − paper, cumulative "
           "re-localization, mean over the ranked features, points):";
    for (const RowSignedDeviation& row : agreement.single_map_rows) {
      out << " " << Cell(row.row) << " " << (row.mean_pts ? FormatSigned(*row.mean_pts, 1) : "–");
    }
    out << "\n\n";
  }
  if (!agreement.features_per_frame.empty()) {
    out << "**Features per frame, measured / paper**:";
    for (const FeatureRatio& f : agreement.features_per_frame) {
      out << " " << f.feature << " " << FormatFixed(f.ratio, 2) << " ("
          << FormatFixed(f.measured, 0) << "/" << FormatFixed(f.paper, 0) << ")";
    }
    out << "\n\n";
  }
}

void ConsecutiveBoundsMarkdown(const std::vector<ConsecutiveBound>& bounds, std::ostream& out) {
  if (bounds.empty()) return;
  out << "**Consecutive sessions, within 55 cm against the paths' bound** (the share had every "
         "frame re-localized: a frame more than 55 cm after the one before never counts; "
         "measured / bound (paper), %):";
  for (const ConsecutiveBound& b : bounds) {
    out << " " << b.row << ":";
    for (size_t i = 0; i < b.features.size(); ++i) {
      out << " " << b.features[i] << " " << FormatFixed(b.measured_pct[i], 0) << "/"
          << FormatFixed(b.bound_pct[i], 0);
      if (b.paper_pct[i]) out << " (" << FormatFixed(*b.paper_pct[i], 0) << ")";
    }
    out << ";";
  }
  out << "\n\n";
}

void FindingsMarkdown(const AgreementReport& agreement, std::ostream& out) {
  out << "**The paper's findings**: " << agreement.FindingsReproduced() << " of "
      << agreement.FindingsDecided() << " decided reproduced\n\n"
      << "| finding | rule | measured | verdict | the rule on the paper's numbers |\n"
      << "| --- | --- | --- | --- | --- |\n";
  for (const FindingCheck& f : agreement.findings) {
    out << "| " << Cell(f.finding) << " | " << (f.criterion.empty() ? "–" : Cell(f.criterion))
        << " | " << Cell(f.measured) << " | " << FindingVerdictName(f.verdict) << " | "
        << Cell(f.paper) << " |\n";
  }
}

}  // namespace

std::string AgreementToMarkdown(const AgreementReport& agreement) {
  std::ostringstream out;
  DeviationsMarkdown(agreement, out);
  RankingMarkdown(agreement.ranking, out);
  MapAndFeatureMarkdown(agreement, out);
  ConsecutiveBoundsMarkdown(agreement.consecutive_bounds, out);
  FindingsMarkdown(agreement, out);
  return out.str();
}

nlohmann::json AgreementToJson(const AgreementReport& agreement) {
  nlohmann::json json;
  json["deviations"] = nlohmann::json::array();
  for (const TableDeviation& d : agreement.deviations) {
    json["deviations"].push_back({{"name", d.name},
                                  {"unit", d.unit},
                                  {"role", AgreementRoleName(d.role)},
                                  {"cells", d.cells},
                                  {"mean_abs_deviation", OptionalJson(d.mean_abs_deviation)},
                                  {"max_abs_deviation", OptionalJson(d.max_abs_deviation)},
                                  {"worst_cell", d.worst_cell}});
  }
  json["ranking"] = {{"features", agreement.ranking.features},
                     {"measured_mean_pct", agreement.ranking.measured_mean_pct},
                     {"paper_mean_pct", agreement.ranking.paper_mean_pct},
                     {"spearman_rho", OptionalJson(agreement.ranking.spearman_rho)},
                     {"spearman_rho_low", OptionalJson(agreement.ranking.spearman_rho_low)},
                     {"spearman_rho_high", OptionalJson(agreement.ranking.spearman_rho_high)},
                     {"rank_resolution_pts", kRankResolutionPts},
                     {"close_pairs", nlohmann::json::array()}};
  for (const ClosePair& pair : agreement.ranking.close_pairs) {
    json["ranking"]["close_pairs"].push_back(
        {{"higher", pair.higher}, {"lower", pair.lower}, {"gap_pts", pair.gap_pts}});
  }
  const NightMinusDay& n = agreement.night_minus_day;
  json["night_minus_day"] = {{"night_row", n.night_row},
                             {"day_row", n.day_row},
                             {"measured_pts", OptionalJson(n.measured_pts)},
                             {"paper_pts", OptionalJson(n.paper_pts)}};
  json["single_map_rows"] = nlohmann::json::array();
  for (const RowSignedDeviation& row : agreement.single_map_rows) {
    json["single_map_rows"].push_back(
        {{"row", row.row}, {"mean_signed_deviation_pts", OptionalJson(row.mean_pts)}, {"features", row.features}});
  }
  json["features_per_frame"] = nlohmann::json::array();
  for (const FeatureRatio& f : agreement.features_per_frame) {
    json["features_per_frame"].push_back(
        {{"feature", f.feature}, {"measured", f.measured}, {"paper", f.paper}, {"ratio", f.ratio}});
  }
  json["consecutive_bounds"] = nlohmann::json::array();
  for (const ConsecutiveBound& b : agreement.consecutive_bounds) {
    nlohmann::json paper = nlohmann::json::array();
    for (const auto& v : b.paper_pct) paper.push_back(OptionalJson(v));
    json["consecutive_bounds"].push_back({{"row", b.row},
                                          {"features", b.features},
                                          {"measured_pct", b.measured_pct},
                                          {"bound_pct", b.bound_pct},
                                          {"paper_pct", paper}});
  }
  json["findings"] = nlohmann::json::array();
  for (const FindingCheck& f : agreement.findings) {
    json["findings"].push_back({{"finding", f.finding},
                                {"criterion", f.criterion},
                                {"verdict", FindingVerdictName(f.verdict)},
                                {"measured", f.measured},
                                {"paper", f.paper}});
  }
  json["findings_reproduced"] = agreement.FindingsReproduced();
  json["findings_decided"] = agreement.FindingsDecided();
  return json;
}

}  // namespace duskmap