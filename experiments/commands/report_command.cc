// `duskmap report`: merges the results folders of one or more runs (the
// shards of a matrix) into the paper's tables, figure data, figures and
// report.md.
#include <iostream>
#include <memory>

#include "experiments/command_registry.h"
#include "experiments/report_summary.h"

namespace duskmap::cli {
namespace {

struct ReportArgs {
  std::string config;
  std::vector<std::string> results;
  std::string output;
  std::string paper;
  bool figures = true;
  bool allow_missing = false;
};

RunFn SetupReport(CLI::App& command) {
  auto args = std::make_shared<ReportArgs>();
  command.add_option("config", args->config, "the experiment config the runs used")->required();
  command.add_option("--results", args->results, "results folders of `duskmap run` (shards)")
      ->required();
  command.add_option("--output", args->output, "report folder")->required();
  command.add_option("--paper", args->paper,
                     "the paper's numbers (default: configs/paper_results.json)");
  command.add_flag("!--no-figures", args->figures, "write the tables only");
  command.add_flag("--allow-missing", args->allow_missing,
                   "exit 0 even when some jobs have no results");
  return [args] {
    ExperimentReportRequest request = ReportRequestFor(
        args->config, std::vector<std::filesystem::path>(args->results.begin(), args->results.end()),
        args->output, args->figures);
    request.paper_results = args->paper;
    request.allow_missing = args->allow_missing;
    const ExperimentReportOutcome outcome = WriteExperimentReport(request);
    PrintReportOutcome(request, outcome);
    const size_t missing = outcome.missing_jobs.size();
    if (missing > 0 && !args->allow_missing) {
      std::cerr << "duskmap: error: " << missing
                << " jobs have no results in the given folders (a shard missing or unfinished; "
                   "--allow-missing writes the partial report)\n";
      return 1;
    }
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"report", "Merge run results (shards) into the paper's tables and figures", &SetupReport});

}  // namespace
}  // namespace duskmap::cli
