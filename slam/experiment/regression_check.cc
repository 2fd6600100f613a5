#include "slam/experiment/regression_check.h"

#include <fstream>
#include <map>
#include <sstream>

#include "slam/core/check.h"

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

double ToDouble(const std::string& text, const std::string& where) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  SLAM_THROW_IF_NOT(InputError, used == text.size() && !text.empty())
      << where << ": '" << text << "' is not a number";
  return value;
}

}  // namespace

std::vector<CellRates> ReadCellRates(const std::string& path) {
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open";
  std::string line;
  SLAM_THROW_IF_NOT(InputError, static_cast<bool>(std::getline(in, line))) << path << ": empty file";
  const std::vector<std::string> header = SplitCsv(line);
  std::map<std::string, size_t> column;
  for (size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  for (const char* name : {"feature", "row", "session", "frames", "relocalized_pct", "correct_pct",
                           "wrong"}) {
    SLAM_THROW_IF_NOT(InputError, column.count(name))
        << path << ": not a report's cells.csv (no column '" << name << "')";
  }
  std::vector<CellRates> cells;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::string where = path + ":" + std::to_string(number);
    const std::vector<std::string> f = SplitCsv(line);
    SLAM_THROW_IF_NOT(InputError, f.size() == header.size())
        << where << ": " << f.size() << " fields, the header has " << header.size();
    CellRates cell;
    cell.feature = f[column["feature"]];
    cell.row = f[column["row"]];
    cell.session = f[column["session"]];
    cell.frames = static_cast<int>(ToDouble(f[column["frames"]], where));
    cell.relocalized_pct = ToDouble(f[column["relocalized_pct"]], where);
    cell.correct_pct = ToDouble(f[column["correct_pct"]], where);
    cell.wrong = static_cast<int>(ToDouble(f[column["wrong"]], where));
    cells.push_back(cell);
  }
  return cells;
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
