// `duskmap check-rates`: the CI regression check. Compares a run's
// re-localization rates (report/cells.csv) with a committed baseline and
// fails when any rate dropped by more than the tolerance.
#include <iomanip>
#include <iostream>
#include <memory>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/report/regression_check.h"

namespace duskmap::cli {
namespace {

struct CheckRatesArgs {
  std::string baseline;
  std::string current;
  RegressionOptions options;
};

RunFn SetupCheckRates(CLI::App& command) {
  auto args = std::make_shared<CheckRatesArgs>();
  command.add_option("--baseline", args->baseline, "committed baseline (a report's cells.csv)")
      ->required();
  command.add_option("--current", args->current, "the run's report/cells.csv")->required();
  command.add_option("--tolerance-pct", args->options.tolerance_pct,
                     "largest allowed drop of a rate, percentage points (default 5)");
  return [args] {
    const RegressionResult result =
        CompareCellRates(ReadCellRates(args->baseline), ReadCellRates(args->current), args->options);
    std::cout << std::fixed << std::setprecision(1);
    for (const RateChange& change : result.improvements) {
      std::cout << "improved: " << change.key << " " << change.metric << " " << change.baseline
                << " -> " << change.current << "\n";
    }
    for (const RateChange& change : result.regressions) {
      std::cout << "REGRESSION: " << change.key << " " << change.metric << " " << change.baseline
                << " -> " << change.current << "\n";
    }
    std::cout << result.cells_compared << " cells compared with " << args->baseline
              << " (tolerance " << args->options.tolerance_pct << " points): "
              << result.regressions.size() << " regressions, " << result.improvements.size()
              << " improvements\n";
    if (!result.improvements.empty() && result.ok()) {
      std::cout << "note: rates improved beyond the tolerance; regenerate the baseline "
                   "deliberately with scripts/update_quick_baseline.sh\n";
    }
    SLAM_THROW_IF_NOT(Error, result.ok())
        << result.regressions.size() << " re-localization rates regressed beyond "
        << args->options.tolerance_pct << " points (see above)";
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"check-rates", "CI regression check: compare re-localization rates with a baseline",
     &SetupCheckRates});

}  // namespace
}  // namespace duskmap::cli
