#include "slam/report/regression_check.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

// Splits one CSV line; fields may be double-quoted (no embedded quotes).
std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

// The number in one field; throws InputError "<where>: <column>: ..." for
// text that is not a number, one beyond double's range ("1e400"), NaN and
// infinity (std::stod reads "nan" and "inf" without complaint).
double ToDouble(const std::string& text, const std::string& where, const char* column) {
  size_t used = 0;
  double value = 0.0;
  bool in_range = true;
  try {
    value = std::stod(text, &used);
  } catch (const std::out_of_range&) {
    in_range = false;
  } catch (const std::exception&) {
    used = 0;
  }
  SLAM_THROW_IF_NOT(InputError, in_range) << where << ": " << column << ": '" << text
                                          << "' is out of range";
  SLAM_THROW_IF_NOT(InputError, used == text.size() && !text.empty())
      << where << ": " << column << ": '" << text << "' is not a number";
  SLAM_THROW_IF_NOT(InputError, std::isfinite(value))
      << where << ": " << column << ": '" << text << "' is not a finite number";
  return value;
}

// A percentage in [0, 100]; with `no_value`, that value too (correct_pct's -1).
double ToPercent(const std::string& text, const std::string& where, const char* column,
                 std::optional<double> no_value = std::nullopt) {
  const double value = ToDouble(text, where, column);
  if (no_value && value == *no_value) return value;
  SLAM_THROW_IF_NOT(InputError, value >= 0.0 && value <= 100.0)
      << where << ": " << column << ": " << text << " is outside [0, 100]";
  return value;
}

// A count in [min, max].
int ToCount(const std::string& text, const std::string& where, const char* column, int min,
            int max) {
  const double value = ToDouble(text, where, column);
  SLAM_THROW_IF_NOT(InputError, value == std::floor(value) && value >= min && value <= max)
      << where << ": " << column << ": " << text << " is not a whole number in [" << min << ", "
      << max << "]";
  return static_cast<int>(value);
}

}  // namespace

std::vector<CellRates> ParseCellRates(std::istream& in, const std::string& path) {
  std::string line;
  SLAM_THROW_IF_NOT(InputError, static_cast<bool>(std::getline(in, line))) << path << ": empty file";
  const std::vector<std::string> header = SplitCsv(line);
  std::map<std::string, size_t> column;
  for (size_t i = 0; i < header.size(); ++i) {
    SLAM_THROW_IF_NOT(InputError, column.emplace(header[i], i).second)
        << path << ":1: column '" << header[i] << "' is given twice";
  }
  for (const char* name : {"feature", "row", "session", "frames", "relocalized_pct", "correct_pct",
                           "wrong"}) {
    SLAM_THROW_IF_NOT(InputError, column.count(name))
        << path << ": not a report's cells.csv (no column '" << name << "')";
  }
  std::vector<CellRates> cells;
  std::map<std::string, int> line_of_cell;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty() || line == "\r") continue;
    const std::string where = path + ":" + std::to_string(number);
    const std::vector<std::string> f = SplitCsv(line);
    SLAM_THROW_IF_NOT(InputError, f.size() == header.size())
        << where << ": " << f.size() << " fields, the header has " << header.size();
    CellRates cell;
    cell.feature = f[column["feature"]];
    cell.row = f[column["row"]];
    cell.session = f[column["session"]];
    // The report writes cells of at least one frame.
    cell.frames = ToCount(f[column["frames"]], where, "frames", 1,
                          std::numeric_limits<int>::max());
    cell.relocalized_pct = ToPercent(f[column["relocalized_pct"]], where, "relocalized_pct");
    // -1: the session has no ground truth.
    cell.correct_pct = ToPercent(f[column["correct_pct"]], where, "correct_pct", -1.0);
    cell.wrong = ToCount(f[column["wrong"]], where, "wrong", 0, cell.frames);
    const auto [first, added] = line_of_cell.emplace(cell.Key(), number);
    SLAM_THROW_IF_NOT(InputError, added) << where << ": cell '" << cell.Key()
                                         << "' is listed twice (first on line " << first->second
                                         << ")";
    cells.push_back(cell);
  }
  return cells;
}

std::vector<CellRates> ReadCellRates(const std::string& path) {
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open";
  return ParseCellRates(in, path);
}

void RegressionOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, tolerance_pct >= 0.0 && tolerance_pct <= 100.0)
      << "tolerance_pct: must be in [0, 100], got " << tolerance_pct;
}

RegressionResult CompareCellRates(const std::vector<CellRates>& baseline,
                                  const std::vector<CellRates>& current,
                                  const RegressionOptions& options) {
  options.Check();
  std::map<std::string, const CellRates*> now;
  for (const CellRates& cell : current) now[cell.Key()] = &cell;
  RegressionResult result;
  const double tol = options.tolerance_pct;
  for (const CellRates& before : baseline) {
    const auto it = now.find(before.Key());
    if (it == now.end() || it->second->frames != before.frames) {
      result.regressions.push_back({before.Key(), "missing", double(before.frames),
                                    it == now.end() ? 0.0 : double(it->second->frames)});
      continue;
    }
    const CellRates& after = *it->second;
    ++result.cells_compared;
    const auto compare = [&](const char* metric, double b, double a, bool higher_is_better) {
      const double gain = higher_is_better ? a - b : b - a;
      if (gain < -tol) result.regressions.push_back({before.Key(), metric, b, a});
      if (gain > tol) result.improvements.push_back({before.Key(), metric, b, a});
    };
    compare("relocalized_pct", before.relocalized_pct, after.relocalized_pct, true);
    if (before.correct_pct >= 0.0) {
      compare("correct_pct", before.correct_pct, after.correct_pct, true);
    }
    if (before.frames > 0) {
      compare("wrong_pct", 100.0 * before.wrong / before.frames,
              100.0 * after.wrong / after.frames, false);
    }
  }
  return result;
}

}  // namespace duskmap
