// How far a report agrees with the paper (issue 18, "agreement section"):
// the mean absolute deviation of each table from the paper's values, the rank
// correlation of the features' ordering, features per frame as a ratio of the
// paper's, the night-minus-day difference, and each of the paper's
// qualitative findings that a number decides, reproduced or not. Computed
// from the report's tables alone, so a run on the paper's released data gets
// the same section.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "slam/report/paper_findings.h"
#include "slam/report/paper_reference.h"
#include "slam/report/report_table.h"
#include "slam/report/session_matrix.h"

namespace duskmap {

// Whether a number may be tuned on when calibrating the synthetic dataset
// (issue 18: the single-session maps and features per frame only).
enum class AgreementRole { kCalibration, kHeldOut };
const char* AgreementRoleName(AgreementRole role);

// Cells of one table (or part of one) that have both a measured and a paper
// value, and how far apart they are.
struct TableDeviation {
  std::string name;  // e.g. "re-localization, single-session maps"
  std::string unit;  // "points", "mm", "m"
  AgreementRole role = AgreementRole::kHeldOut;
  int cells = 0;
  std::optional<double> mean_abs_deviation;
  std::optional<double> max_abs_deviation;
  std::string worst_cell;  // "KA on 6: 22 (paper 72)"
};

struct FeatureRatio {
  std::string feature;
  double measured = 0.0;
  double paper = 0.0;
  double ratio = 0.0;  // measured / paper
};

// Measured feature means closer than this are not an order one run decides:
// the same config with another seed moved the features' single-map means by
// up to 0.7 points and the gaps between them by up to 1.3 (docs/experiments.md,
// "Agreement with the paper").
inline constexpr double kRankResolutionPts = 1.0;

// Two ranked features whose measured means lie within kRankResolutionPts.
struct ClosePair {
  std::string higher;  // the one measured higher (first in the ranked list on a tie)
  std::string lower;
  double gap_pts = 0.0;
};

// The features ordered by their mean single-session-map re-localization.
struct RankAgreement {
  std::vector<std::string> features;  // those with both values in every single-session row
  std::vector<double> measured_mean_pct;
  std::vector<double> paper_mean_pct;
  std::optional<double> spearman_rho;  // nullopt below 3 features
  // Spearman's rho over every measured order that keeps features at least
  // kRankResolutionPts apart in their measured order and lets closer ones
  // swap: how far the ranking is decided. Both equal spearman_rho when no two
  // features are that close; nullopt with it, or above kMaxFeaturesForRhoRange.
  std::optional<double> spearman_rho_low;
  std::optional<double> spearman_rho_high;
  std::vector<ClosePair> close_pairs;  // in the order of `features`
};
inline constexpr size_t kMaxFeaturesForRhoRange = 9;  // 9! orders at most

// The latest single-session map minus the earliest, cumulative re-localization
// averaged over the ranked features (the paper: map 6 - map 1 = +8.8 points).
struct NightMinusDay {
  std::string night_row;
  std::string day_row;
  std::optional<double> measured_pts;
  std::optional<double> paper_pts;
};

// One single-session map's row, measured minus paper, averaged over the
// ranked features: where a calibration stands map by map (the mean absolute
// deviation hides a day map that is too good behind a night map too weak).
struct RowSignedDeviation {
  std::string row;
  std::optional<double> mean_pts;  // nullopt when no ranked feature has both values
  int features = 0;                // the ranked features with both values
};

// One consecutive-session gap class: the frames re-localized within 55 cm
// against the paths' bound (the share had every frame re-localized: a frame
// more than 55 cm after the one before never counts) and the paper's value.
// A paper value above the bound is out of reach on these paths, whatever the
// features do.
struct ConsecutiveBound {
  std::string row;                    // "30 min"
  std::vector<std::string> features;  // those with a measured share and bound
  std::vector<double> measured_pct;
  std::vector<double> bound_pct;
  std::vector<std::optional<double>> paper_pct;
};

struct AgreementReport {
  std::vector<TableDeviation> deviations;
  RankAgreement ranking;
  NightMinusDay night_minus_day;
  std::vector<RowSignedDeviation> single_map_rows;  // in the table's row order
  std::vector<FeatureRatio> features_per_frame;
  std::vector<ConsecutiveBound> consecutive_bounds;  // empty without the bound table
  std::vector<FindingCheck> findings;

  int FindingsReproduced() const;
  int FindingsDecided() const;
  const TableDeviation* FindDeviation(const std::string& name) const;
};

// Names of the deviation entries always computed (others: one per
// consecutive-session gap class, "consecutive <class>: ...").
inline constexpr char kDeviationSingleMaps[] = "re-localization, single-session maps";
inline constexpr char kDeviationMultiMaps[] = "re-localization, multi-session maps";
inline constexpr char kDeviationInliers[] = "visual inliers";
inline constexpr char kDeviationJumps[] = "re-localization jumps";

// `tables` as BuildReport makes them (found by ReportTable::id; absent tables
// leave their entries empty); `single_maps` for the diagonal finding.
AgreementReport ComputeAgreement(const std::vector<ReportTable>& tables,
                                 const SingleMapMatrix& single_maps, const PaperReference& paper);

// Spearman's rank correlation (average ranks for ties); nullopt when the
// sizes differ, below 3 values, or a side is constant.
std::optional<double> SpearmanRho(const std::vector<double>& a, const std::vector<double>& b);

// The lowest and highest SpearmanRho(order, reference) over the orders of
// `measured` that keep every pair at least `resolution` apart as measured
// (RankAgreement::spearman_rho_low/high); nullopt when SpearmanRho is, or
// above kMaxFeaturesForRhoRange values.
std::optional<std::pair<double, double>> SpearmanRhoRange(const std::vector<double>& measured,
                                                          const std::vector<double>& reference,
                                                          double resolution);

std::string AgreementToMarkdown(const AgreementReport& agreement);
nlohmann::json AgreementToJson(const AgreementReport& agreement);

}  // namespace duskmap
