#include "slam/report/report_cells.h"

namespace duskmap {

std::string FormatSigned(double value, int decimals) {
  return (value >= 0.0 ? "+" : "") + FormatFixed(value, decimals);
}

const ReportTable* FindTable(const std::vector<ReportTable>& tables, const std::string& id) {
  for (const ReportTable& table : tables) {
    if (table.id() == id) return &table;
  }
  return nullptr;
}

std::optional<double> CellValue(const ReportTable* table, const std::string& row,
                                const std::string& column, TableSide side) {
  if (table == nullptr || !table->HasRow(row) || !table->HasColumn(column)) return std::nullopt;
  const TableCell& cell = table->At(row, column);
  return side == TableSide::kMeasured ? cell.measured : cell.paper;
}

bool IsSingleSessionRow(const std::string& row) {
  try {
    return ParseMapSpec(row).kind == MapKind::kSingle;
  } catch (const std::exception&) {
    return false;
  }
}

std::optional<MapSpec> RowMapSpec(const std::string& row) {
  try {
    return ParseMapSpec(row);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::vector<std::string> SingleSessionRows(const ReportTable* table) {
  std::vector<std::string> rows;
  if (table == nullptr) return rows;
  for (const std::string& row : table->rows()) {
    if (IsSingleSessionRow(row)) rows.push_back(row);
  }
  return rows;
}

std::vector<std::string> PaperColumns(const ReportTable* table) {
  std::vector<std::string> columns;
  if (table == nullptr) return columns;
  for (const std::string& column : table->columns()) {
    for (const std::string& row : table->rows()) {
      if (table->At(row, column).paper) {
        columns.push_back(column);
        break;
      }
    }
  }
  return columns;
}

std::optional<double> RowMean(const ReportTable* table, const std::vector<std::string>& rows,
                              const std::string& column, TableSide side) {
  if (rows.empty()) return std::nullopt;
  double sum = 0.0;
  for (const std::string& row : rows) {
    const auto value = CellValue(table, row, column, side);
    if (!value) return std::nullopt;
    sum += *value;
  }
  return sum / rows.size();
}

}  // namespace duskmap
