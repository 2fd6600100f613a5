#include "slam/report/paper_reference.h"

#include <algorithm>
#include <map>
#include <set>

#include "slam/core/json_fields.h"
#include "slam/report/report_table.h"

namespace duskmap {
namespace {

// The keys of a paper file: what the report reads, and what documents it.
// Rows below a table's metrics (map names, gap classes) are the paper's own.
const std::set<std::string>& DescriptiveKeys() {
  static const std::set<std::string> keys = {"source", "features", "feature_order", "sessions",
                                             "map_notation", "parameters", "notes"};
  return keys;
}

// Each table the report fills, with the keys it holds besides "caption",
// "columns", "note" and "<key>_note"; an empty set: its keys are its rows.
const std::map<std::string, std::set<std::string>>& TableKeys() {
  static const std::map<std::string, std::set<std::string>> keys = {
      {"table_cumulative_relocalization", {"relocalization_pct", "visual_inliers_pct", "jumps_mm"}},
      {"table_ram_mb", {"nodes", "ram_mb", "constant_overhead_mb"}},
      {"table_reduced_graph", {"nodes", "reduction_pct"}},
      {"table_timing",
       {"feature_detection_ms", "loop_closure_detection_ms", "transformation_estimation_ms",
        "features_per_frame", "vocabulary_size_thousands", "descriptor_dimension",
        "descriptor_bytes_per_element"}},
      {"table_ate_mm", {}},
      {"table_gap_distance", {}}};
  return keys;
}

bool IsNoteKey(const std::string& key) {
  return key == "note" || (key.size() > 5 && key.compare(key.size() - 5, 5, "_note") == 0);
}

// A misspelt key would leave its values out of the report without a word:
// unknown keys are refused, naming the file and the key.
void CheckPaperKeys(const nlohmann::json& root, const std::string& path) {
  SLAM_THROW_IF_NOT(ConfigError, root.is_object()) << path << ": expected a JSON object (the paper's values)";
  for (auto it = root.begin(); it != root.end(); ++it) {
    const std::string& key = it.key();
    if (key == JsonFields::kCommentKey || DescriptiveKeys().count(key) > 0) continue;
    if (key == "qualitative_findings") {
      SLAM_THROW_IF_NOT(ConfigError, it->is_array()) << path << ": qualitative_findings: expected a list of texts";
      for (const nlohmann::json& finding : *it) {
        SLAM_THROW_IF_NOT(ConfigError, finding.is_string())
            << path << ": qualitative_findings: expected a list of texts";
      }
      continue;
    }
    const auto table = TableKeys().find(key);
    SLAM_THROW_IF_NOT(ConfigError, table != TableKeys().end())
        << path << ": unknown key '" << key << "' (the report reads qualitative_findings and "
        << "table_cumulative_relocalization, table_ram_mb, table_reduced_graph, table_timing, "
        << "table_ate_mm, table_gap_distance)";
    SLAM_THROW_IF_NOT(ConfigError, it->is_object()) << path << ": " << key << ": expected an object";
    const nlohmann::json columns = it->value("columns", nlohmann::json());
    SLAM_THROW_IF_NOT(ConfigError, columns.is_array() && !columns.empty() &&
                                       std::all_of(columns.begin(), columns.end(),
                                                   [](const nlohmann::json& c) { return c.is_string(); }))
        << path << ": " << key << ".columns: expected a list of feature codes";
    if (table->second.empty()) continue;
    for (auto field = it->begin(); field != it->end(); ++field) {
      const std::string& name = field.key();
      SLAM_THROW_IF_NOT(ConfigError, name == "caption" || name == "columns" || name == JsonFields::kCommentKey ||
                                         IsNoteKey(name) || table->second.count(name) > 0)
          << path << ": unknown key '" << key << "." << name << "'";
    }
  }
}

}  // namespace

PaperReference PaperReference::Load(const std::string& path) {
  nlohmann::json root = ReadJsonFile(path);
  CheckPaperKeys(root, path);
  return PaperReference(std::move(root));
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
