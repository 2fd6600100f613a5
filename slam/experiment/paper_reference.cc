#include "slam/experiment/paper_reference.h"

#include <algorithm>

#include "slam/core/json_fields.h"
#include "slam/experiment/report_table.h"

namespace duskmap {

PaperReference PaperReference::Load(const std::string& path) {
  return PaperReference(ReadJsonFile(path));
}

std::optional<double> PaperReference::Value(const std::vector<std::string>& keys,
                                            const std::string& column) const {
  if (keys.empty() || !root_.contains(keys.front())) return std::nullopt;
  const nlohmann::json& table = root_.at(keys.front());
  const nlohmann::json* node = &table;
  for (size_t i = 1; i < keys.size(); ++i) {
    if (!node->is_object() || !node->contains(keys[i])) return std::nullopt;
    node = &node->at(keys[i]);
  }
  if (node->is_number()) return node->get<double>();
  if (!node->is_array() || !table.contains("columns")) return std::nullopt;
  const auto columns = table.at("columns").get<std::vector<std::string>>();
  const auto it = std::find(columns.begin(), columns.end(), column);
  if (it == columns.end()) return std::nullopt;
  const size_t index = static_cast<size_t>(it - columns.begin());
  if (index >= node->size() || !node->at(index).is_number()) return std::nullopt;
  return node->at(index).get<double>();
}

std::vector<std::string> PaperReference::Findings() const {
  std::vector<std::string> findings;
  const auto it = root_.find("qualitative_findings");
  if (it == root_.end() || !it->is_array()) return findings;
  for (const nlohmann::json& finding : *it) {
    if (finding.is_string()) findings.push_back(finding.get<std::string>());
  }
  return findings;
}

void PaperReference::FillRows(const std::string& table_key, const std::string& metric_key,
                              ReportTable* table) const {
  for (const std::string& row : table->rows()) {
    for (const std::string& column : table->columns()) {
      std::vector<std::string> keys = {table_key};
      if (!metric_key.empty()) keys.push_back(metric_key);
      keys.push_back(row);
      if (const auto value = Value(keys, column)) table->SetPaper(row, column, *value);
    }
  }
}

}  // namespace duskmap
