// A table laid out like the paper's: row labels (maps), column labels
// (feature codes), each cell the value duskmap measured and, where the paper
// reports one, the paper's value beside it. Written as Markdown, CSV or LaTeX.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace duskmap {

struct TableCell {
  std::optional<double> measured;
  std::optional<double> paper;
};

// `value` with `decimals` digits after the point ("12.3"), as the tables
// print their cells.
std::string FormatFixed(double value, int decimals);

class ReportTable {
 public:
  // `id` names the table for code that reads it back (report_table_ids.h);
  // `caption` is what readers see.
  ReportTable(std::string id, std::string caption, std::vector<std::string> rows,
              std::vector<std::string> columns, int decimals = 0);

  void SetMeasured(const std::string& row, const std::string& column, double value);
  void SetPaper(const std::string& row, const std::string& column, double value);
  const TableCell& At(const std::string& row, const std::string& column) const;

  const std::string& id() const { return id_; }
  const std::string& caption() const { return caption_; }
  bool HasRow(const std::string& row) const;
  bool HasColumn(const std::string& column) const;
  const std::vector<std::string>& rows() const { return rows_; }
  const std::vector<std::string>& columns() const { return columns_; }

  // Cells read "measured (paper)"; "–" where nothing was measured.
  std::string ToMarkdown() const;
  // One line per cell: row,column,measured,paper (empty when absent).
  std::string ToCsv() const;
  // A tabular environment with the caption as a comment line.
  std::string ToLatex() const;

 private:
  size_t RowIndex(const std::string& row) const;
  size_t ColumnIndex(const std::string& column) const;
  std::string FormatCell(const TableCell& cell, bool latex) const;

  std::string id_;
  std::string caption_;
  std::vector<std::string> rows_;
  std::vector<std::string> columns_;
  int decimals_;
  std::vector<TableCell> cells_;  // row-major
};

}  // namespace duskmap
