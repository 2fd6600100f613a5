// The paper's published numbers (configs/paper_results.json, the same file as
// ../shared/reference/paper_results.json), looked up by table, key path, and
// feature column, so every report cell can show the paper's value beside ours.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace duskmap {

class ReportTable;

class PaperReference {
 public:
  // Throws ConfigError("<path>: ...") when the file cannot be read, and for a
  // key the report does not know ("<path>: unknown key 'table_ate'"): the
  // tables it fills, their metrics, qualitative_findings, and the keys that
  // describe the paper (source, features, sessions, ...; docs/experiments.md).
  static PaperReference Load(const std::string& path);
  explicit PaperReference(nlohmann::json root) : root_(std::move(root)) {}

  // The value at root[keys[0]][keys[1]]...; when that is an array it is
  // indexed by the position of `column` in root[keys[0]]["columns"]; when it is
  // a number it is returned as is. nullopt when the paper has no such value.
  std::optional<double> Value(const std::vector<std::string>& keys,
                              const std::string& column) const;

  // The paper's qualitative findings (root["qualitative_findings"]), empty
  // when the file lists none.
  std::vector<std::string> Findings() const;

  // Fills the paper value of every cell of `table` whose row exists under
  // root[table_key][metric_key] (rows = table rows, columns = feature codes).
  void FillRows(const std::string& table_key, const std::string& metric_key,
                ReportTable* table) const;

 private:
  nlohmann::json root_;
};

}  // namespace duskmap
