#include "experiments/report_summary.h"

#include <iostream>
#include <optional>

#include "slam/report/report_table.h"

namespace duskmap::cli {
namespace fs = std::filesystem;
namespace {

std::string Number(const std::optional<double>& value, int decimals) {
  return value ? FormatFixed(*value, decimals) : std::string("-");
}

void PrintAgreement(const AgreementReport& agreement, const fs::path& output_dir) {
  const TableDeviation* single = agreement.FindDeviation(kDeviationSingleMaps);
  const TableDeviation* multi = agreement.FindDeviation(kDeviationMultiMaps);
  std::cout << "agreement with the paper: single-session maps deviate by "
            << Number(single->mean_abs_deviation, 1) << " points, multi-session maps by "
            << Number(multi->mean_abs_deviation, 1) << " (held out), Spearman rho "
            << Number(agreement.ranking.spearman_rho, 2);
  const RankAgreement& ranking = agreement.ranking;
  if (!ranking.close_pairs.empty() && ranking.spearman_rho_low && ranking.spearman_rho_high) {
    std::cout << " (" << FormatFixed(*ranking.spearman_rho_low, 2) << " to "
              << FormatFixed(*ranking.spearman_rho_high, 2) << " over the orders of features within "
              << FormatFixed(kRankResolutionPts, 1) << " points)";
  }
  std::cout << ", findings reproduced "
            << agreement.FindingsReproduced() << "/" << agreement.FindingsDecided() << " ("
            << (output_dir / "agreement.md").string() << ")\n";
}

}  // namespace

ExperimentReportRequest ReportRequestFor(const std::string& config_path,
                                         std::vector<fs::path> results_dirs,
                                         const fs::path& output_dir, bool figures) {
  ExperimentReportRequest request;
  request.config_path = config_path;
  request.results_dirs = std::move(results_dirs);
  request.output_dir = output_dir;
  request.default_paper_results = fs::path(DUSKMAP_SOURCE_DIR) / "configs" / "paper_results.json";
  request.figures = figures;
  request.plot_script = fs::path(DUSKMAP_SOURCE_DIR) / "scripts" / "plot_report.py";
  return request;
}

void PrintReportOutcome(const ExperimentReportRequest& request,
                        const ExperimentReportOutcome& outcome) {
  for (const SkippedFeature& skipped : outcome.skipped_features) {
    std::cout << "note: feature " << skipped.label << " skipped: " << skipped.reason << "\n";
  }
  if (!outcome.missing_jobs.empty()) {
    std::cout << "note: " << outcome.missing_jobs.size()
              << " jobs have no results yet (their cells are empty), e.g. "
              << outcome.missing_jobs.front() << "\n";
  }
  std::cout << "tables: " << (request.output_dir / "tables.md").string() << "\n";
  if (outcome.agreement) PrintAgreement(*outcome.agreement, request.output_dir);
  if (request.figures && !outcome.figures_drawn) {
    std::cout << "note: figures not drawn (scripts/plot_report.py failed; see its error "
                 "above)\n";
  } else if (request.figures) {
    std::cout << "report: " << (request.output_dir / "report.md").string() << "\n";
  }
}

}  // namespace duskmap::cli
