// Reading a built report's tables back (by ReportTable::id): a cell's
// measured or paper value, which rows are single-session maps, which columns
// the paper reports. Shared by the agreement section and the paper's findings;
// and the mean the tables take over jobs (OptionalMean).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slam/experiment/map_spec.h"
#include "slam/report/report_table.h"

namespace duskmap {

enum class TableSide { kMeasured, kPaper };

// nullptr when no table has that id.
const ReportTable* FindTable(const std::vector<ReportTable>& tables, const std::string& id);

// nullopt when the table is null, lacks the row or column, or the cell the side.
std::optional<double> CellValue(const ReportTable* table, const std::string& row,
                                const std::string& column, TableSide side);

// The row's map spec, nullopt for a row that is no map label ("30 min").
std::optional<MapSpec> RowMapSpec(const std::string& row);
bool IsSingleSessionRow(const std::string& row);
std::vector<std::string> SingleSessionRows(const ReportTable* table);

// Columns with at least one paper value.
std::vector<std::string> PaperColumns(const ReportTable* table);

// The mean of a column over `rows` on one side; nullopt when any is missing.
std::optional<double> RowMean(const ReportTable* table, const std::vector<std::string>& rows,
                              const std::string& column, TableSide side);

// The mean of the values added, empty when none was (a measure no job took).
struct OptionalMean {
  double sum = 0.0;
  int count = 0;
  void Add(double value) {
    sum += value;
    ++count;
  }
  std::optional<double> Get() const {
    return count > 0 ? std::optional<double>(sum / count) : std::nullopt;
  }
};

// FormatFixed (report_table.h) with the sign: "+1.5", "-0.3".
std::string FormatSigned(double value, int decimals);

}  // namespace duskmap
