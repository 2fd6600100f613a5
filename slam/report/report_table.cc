#include "slam/report/report_table.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "slam/core/check.h"

namespace duskmap {
namespace {

std::string EscapeLatex(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "$|$";
    } else if (c == '_' || c == '%' || c == '&' || c == '#') {
      out += '\\';
      out += c;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string FormatFixed(double value, int decimals) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << value;
  return out.str();
}

ReportTable::ReportTable(std::string id, std::string caption, std::vector<std::string> rows,
                         std::vector<std::string> columns, int decimals)
    : id_(std::move(id)),
      caption_(std::move(caption)),
      rows_(std::move(rows)),
      columns_(std::move(columns)),
      decimals_(decimals),
      cells_(rows_.size() * columns_.size()) {}

bool ReportTable::HasRow(const std::string& row) const {
  return std::find(rows_.begin(), rows_.end(), row) != rows_.end();
}

bool ReportTable::HasColumn(const std::string& column) const {
  return std::find(columns_.begin(), columns_.end(), column) != columns_.end();
}

size_t ReportTable::RowIndex(const std::string& row) const {
  const auto it = std::find(rows_.begin(), rows_.end(), row);
  SLAM_CHECK_MSG(it != rows_.end(), "unknown row " + row);
  return static_cast<size_t>(it - rows_.begin());
}

size_t ReportTable::ColumnIndex(const std::string& column) const {
  const auto it = std::find(columns_.begin(), columns_.end(), column);
  SLAM_CHECK_MSG(it != columns_.end(), "unknown column " + column);
  return static_cast<size_t>(it - columns_.begin());
}

void ReportTable::SetMeasured(const std::string& row, const std::string& column, double value) {
  cells_[RowIndex(row) * columns_.size() + ColumnIndex(column)].measured = value;
}

void ReportTable::SetPaper(const std::string& row, const std::string& column, double value) {
  cells_[RowIndex(row) * columns_.size() + ColumnIndex(column)].paper = value;
}

const TableCell& ReportTable::At(const std::string& row, const std::string& column) const {
  return cells_[RowIndex(row) * columns_.size() + ColumnIndex(column)];
}

std::string ReportTable::FormatCell(const TableCell& cell, bool latex) const {
  std::string text = cell.measured ? FormatFixed(*cell.measured, decimals_) : "–";
  if (latex && !cell.measured) text = "--";
  if (cell.paper) text += " (" + FormatFixed(*cell.paper, decimals_) + ")";
  return text;
}

std::string ReportTable::ToMarkdown() const {
  std::ostringstream out;
  out << "**" << caption_ << "** — measured (paper)\n\n| map |";
  for (const std::string& column : columns_) out << " " << column << " |";
  out << "\n| --- |";
  for (size_t c = 0; c < columns_.size(); ++c) out << " ---: |";
  out << "\n";
  for (size_t r = 0; r < rows_.size(); ++r) {
    std::string label;  // a '|' inside a cell must be escaped in Markdown tables
    for (char c : rows_[r]) label += c == '|' ? std::string("\\|") : std::string(1, c);
    out << "| " << label << " |";
    for (size_t c = 0; c < columns_.size(); ++c) {
      out << " " << FormatCell(cells_[r * columns_.size() + c], false) << " |";
    }
    out << "\n";
  }
  return out.str();
}

std::string ReportTable::ToCsv() const {
  std::ostringstream out;
  out << "row,column,measured,paper\n";
  for (size_t r = 0; r < rows_.size(); ++r) {
    for (size_t c = 0; c < columns_.size(); ++c) {
      const TableCell& cell = cells_[r * columns_.size() + c];
      out << '"' << rows_[r] << "\"," << columns_[c] << ","
          << (cell.measured ? FormatFixed(*cell.measured, decimals_ + 2) : "") << ","
          << (cell.paper ? FormatFixed(*cell.paper, decimals_ + 2) : "") << "\n";
    }
  }
  return out.str();
}

std::string ReportTable::ToLatex() const {
  std::ostringstream out;
  out << "% " << caption_ << " -- measured (paper)\n\\begin{tabular}{l";
  for (size_t c = 0; c < columns_.size(); ++c) out << "r";
  out << "}\n\\hline\nmap";
  for (const std::string& column : columns_) out << " & " << EscapeLatex(column);
  out << " \\\\\n\\hline\n";
  for (size_t r = 0; r < rows_.size(); ++r) {
    out << EscapeLatex(rows_[r]);
    for (size_t c = 0; c < columns_.size(); ++c) {
      out << " & " << FormatCell(cells_[r * columns_.size() + c], true);
    }
    out << " \\\\\n";
  }
  out << "\\hline\n\\end{tabular}\n";
  return out.str();
}

}  // namespace duskmap
