// libFuzzer target: the rates reader of `duskmap check-rates` (a CI gate).
// Any input either throws duskmap::Error (one line) or gives cells whose
// rates are finite and in [0, 100] (correct_pct: or -1), frames >= 1, wrong
// in [0, frames], and no cell twice; comparing them with themselves finds no
// regression and no improvement.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>

#include "slam/core/check.h"
#include "slam/report/regression_check.h"

namespace {

bool IsRate(double value) { return std::isfinite(value) && value >= 0.0 && value <= 100.0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<duskmap::CellRates> cells;
  try {
    cells = duskmap::ParseCellRates(in, "fuzz.csv");
  } catch (const duskmap::Error& e) {
    const std::string message = e.what();
    if (message.rfind("fuzz.csv", 0) != 0 || message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  std::set<std::string> keys;
  for (const duskmap::CellRates& cell : cells) {
    if (!IsRate(cell.relocalized_pct)) std::abort();
    if (!(IsRate(cell.correct_pct) || cell.correct_pct == -1.0)) std::abort();
    if (cell.frames < 1 || cell.wrong < 0 || cell.wrong > cell.frames) std::abort();
    if (!keys.insert(cell.Key()).second) std::abort();
  }
  const duskmap::RegressionResult same =
      duskmap::CompareCellRates(cells, cells, duskmap::RegressionOptions());
  if (!same.ok() || !same.improvements.empty() ||
      same.cells_compared != static_cast<int>(cells.size())) {
    std::abort();
  }
  return 0;
}
