#include "slam/engine/record_io.h"

#include <map>
#include <set>

#include "slam/core/check.h"
#include "slam/core/json_codec.h"
#include "slam/engine/localization_record_json.h"
#include "slam/engine/mapper_json.h"
#include "slam/io/trajectory_io.h"

namespace duskmap {
namespace {

nlohmann::json PoseToJson(const Rigid3d& pose) {
  return {{"t", {pose.translation.x(), pose.translation.y(), pose.translation.z()}},
          {"q_xyzw", {pose.rotation.x(), pose.rotation.y(), pose.rotation.z(), pose.rotation.w()}}};
}

void Flatten(const nlohmann::json& value, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>* cells) {
  if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it) {
      Flatten(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key(), cells);
    }
  } else if (value.is_null()) {
    cells->emplace_back(prefix, "");
  } else if (value.is_string()) {
    cells->emplace_back(prefix, value.get<std::string>());
  } else if (value.is_array()) {
    std::string joined;
    for (const auto& v : value) joined += (joined.empty() ? "" : " ") + v.dump();
    cells->emplace_back(prefix, joined);
  } else {
    cells->emplace_back(prefix, value.dump());
  }
}

// RFC 4180 quoting: a field with a comma, quote or line break is quoted, its
// quotes doubled (lists of candidate attempts are JSON with commas).
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

// The keys that are one field each go through the codecs' writer (enums by
// name, std::optional as null); the others are said here: null unless the
// frame re-localized (matched_*), 0 meaning none (lcd_hypothesis), the pose as
// {"t", "q_xyzw"}, the best places' adjusted likelihood as "likelihood", and
// the ground-truth check as three keys of the record.
nlohmann::json LocalizationRecordToJson(const LocalizationRecord& r) {
  nlohmann::json j = nlohmann::json::object();
  JsonCodecWriter f(&j);
  f("frame", r.frame_index);
  f("timestamp_s", r.timestamp_s);
  f("relocalized", r.relocalized);
  f("outcome", r.outcome);
  f("lcd_status", r.lcd_status);
  f("registration_status", r.registration_status);
  f("lcd_score", r.lcd_score);
  f("candidates_tried", r.candidates_tried);
  f("attempts", r.attempts);
  f("proximity_candidates", r.proximity_candidates);
  f("inliers", r.inliers);
  f("cache_validation", r.cache_validation);
  f("features", r.num_features);
  f("jump_mm", r.jump_mm);
  f("distance_since_last_m", r.distance_since_last_m);
  f("timings_ms", r.timings);
  j["lcd_hypothesis"] = r.lcd_hypothesis ? nlohmann::json(r.lcd_hypothesis) : nlohmann::json(nullptr);
  nlohmann::json top = nlohmann::json::array();
  for (const LcdHypothesis& h : r.lcd_top) {
    top.push_back({{"node", h.node}, {"posterior", h.posterior}, {"likelihood", h.adjusted_likelihood}});
  }
  j["lcd_top"] = top;
  j["matched_node"] = r.relocalized ? nlohmann::json(r.matched_node) : nlohmann::json(nullptr);
  j["matched_session"] =
      r.relocalized ? nlohmann::json(r.matched_session) : nlohmann::json(nullptr);
  j["matched_by"] =
      r.relocalized ? nlohmann::json(JsonEnumName(r.matched_by)) : nlohmann::json(nullptr);
  j["pose"] = r.map_from_camera ? PoseToJson(*r.map_from_camera) : nlohmann::json(nullptr);
  if (r.check) {
    j["correct"] = r.check->correct;
    j["error_m"] = r.check->error.translation_m;
    j["error_deg"] = r.check->error.rotation_deg;
  } else {
    j["correct"] = nullptr;
    j["error_m"] = nullptr;
    j["error_deg"] = nullptr;
  }
  return j;
}

// "optimization" is the status of the frame's optimisation, or "none" when
// none ran: two fields in one key, said here.
nlohmann::json MappingResultToJson(const MappingFrameResult& r) {
  nlohmann::json j = nlohmann::json::object();
  JsonCodecWriter f(&j);
  f("node", r.node);
  f("session", r.session);
  f("features", r.num_features);
  f("lcd_status", r.lcd_status);
  f("lcd_hypothesis", r.lcd_hypothesis);
  f("registrations", r.registrations);
  f("loop_closures_added", r.loop_closures_added);
  f("proximity_links_added", r.proximity_links_added);
  f("links_rejected", r.links_rejected);
  f("nodes_reduced", r.nodes_reduced);
  f("timings_ms", r.timings);
  j["optimization"] = r.optimized ? OptimizationStatusName(r.optimization_status) : "none";
  return j;
}

void WriteJsonLines(std::ostream& out, const std::vector<nlohmann::json>& rows) {
  for (const auto& row : rows) out << row.dump() << '\n';
}

void WriteCsv(std::ostream& out, const std::vector<nlohmann::json>& rows) {
  // Columns: every flattened key of any row, in first-seen order (a pose is
  // null before the first re-localization and an object afterwards).
  std::vector<std::string> header;
  std::set<std::string> seen;
  for (const auto& row : rows) {
    std::vector<std::pair<std::string, std::string>> cells;
    Flatten(row, "", &cells);
    for (const auto& cell : cells) {
      if (seen.insert(cell.first).second) header.push_back(cell.first);
    }
  }
  for (size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << header[i];
  out << '\n';
  for (const auto& row : rows) {
    std::vector<std::pair<std::string, std::string>> cells;
    Flatten(row, "", &cells);
    std::map<std::string, std::string> by_key(cells.begin(), cells.end());
    for (size_t i = 0; i < header.size(); ++i) {
      auto it = by_key.find(header[i]);
      out << (i ? "," : "") << (it == by_key.end() ? "" : CsvField(it->second));
    }
    out << '\n';
  }
}

void WriteCorrectedTrajectory(const std::string& path,
                              const std::vector<LocalizationRecord>& records) {
  std::vector<TrajectoryPose> poses;
  for (const LocalizationRecord& r : records) {
    if (r.map_from_camera) poses.push_back({r.timestamp_s, *r.map_from_camera});
  }
  WriteTrajectory(path, poses, "corrected camera poses (map_from_camera), duskmap localize");
}

}  // namespace duskmap
