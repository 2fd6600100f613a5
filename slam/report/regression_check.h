// The CI regression check: compares the re-localization rates of a run
// (cells.csv of its report) with a committed baseline, cell by cell
// (feature x map x localization session), and reports every rate that
// dropped by more than the tolerance. The check never writes the baseline:
// it is regenerated deliberately (scripts/update_quick_baseline.sh).
#pragma once

#include <istream>
#include <string>
#include <vector>

namespace duskmap {

// One matrix cell's rates, as the report's cells.csv lists them.
struct CellRates {
  std::string feature;
  std::string row;      // map label as reported, e.g. "1+3+5"
  std::string session;  // localization session
  int frames = 0;
  double relocalized_pct = 0.0;
  double correct_pct = -1.0;  // < 0 without ground truth
  int wrong = 0;

  std::string Key() const { return feature + " " + row + " " + session; }
};

// Reads a report's cells.csv; throws InputError "<path>:<line>: <column>:
// <problem>" for a value that is not a number, NaN or infinite, a rate outside
// [0, 100] (correct_pct: or -1, no ground truth), frames that are not a whole
// number >= 1, wrong re-localizations that are not a whole number in [0,
// frames], and a cell (feature, row, session) listed twice: the check is a CI
// gate, and a broken run's file must not pass it.
std::vector<CellRates> ReadCellRates(const std::string& path);
// The same for text already open; `path` names it in errors.
std::vector<CellRates> ParseCellRates(std::istream& in, const std::string& path);

struct RegressionOptions {
  // Largest allowed drop of a rate, percentage points of the cell's frames.
  double tolerance_pct = 5.0;
  void Check() const;
};

struct RateChange {
  std::string key;
  std::string metric;  // "relocalized_pct", "correct_pct", "wrong_pct", "missing"
  double baseline = 0.0;
  double current = 0.0;
};

struct RegressionResult {
  int cells_compared = 0;
  std::vector<RateChange> regressions;   // beyond the tolerance, or cells missing
  std::vector<RateChange> improvements;  // rates up by more than the tolerance
  bool ok() const { return regressions.empty(); }
};

// Every baseline cell must exist in `current` with the same number of frames
// (else a "missing" regression); its re-localized and correct rates may not
// drop, nor its wrong re-localizations (as % of frames) rise, by more than
// the tolerance. Cells only in `current` are ignored.
RegressionResult CompareCellRates(const std::vector<CellRates>& baseline,
                                  const std::vector<CellRates>& current,
                                  const RegressionOptions& options);

}  // namespace duskmap
