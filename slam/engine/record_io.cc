#include "slam/engine/record_io.h"

#include <map>
#include <set>

#include "slam/core/check.h"
#include "slam/io/trajectory_io.h"

namespace duskmap {
namespace {

nlohmann::json PoseToJson(const Rigid3d& pose) {
  return {{"t", {pose.translation.x(), pose.translation.y(), pose.translation.z()}},
          {"q_xyzw", {pose.rotation.x(), pose.rotation.y(), pose.rotation.z(), pose.rotation.w()}}};
}

template <typename T>
nlohmann::json Optional(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
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

nlohmann::json LocalizationRecordToJson(const LocalizationRecord& r) {
  nlohmann::json j;
  j["frame"] = r.frame_index;
  j["timestamp_s"] = r.timestamp_s;
  j["relocalized"] = r.relocalized;
  j["outcome"] = LocalizationOutcomeName(r.outcome);
  j["lcd_status"] = LcdStatusName(r.lcd_status);
  j["registration_status"] =
      r.registration_status ? nlohmann::json(RegistrationStatusName(*r.registration_status))
                            : nlohmann::json(nullptr);
  j["lcd_hypothesis"] = r.lcd_hypothesis ? nlohmann::json(r.lcd_hypothesis) : nlohmann::json(nullptr);
  j["lcd_score"] = r.lcd_score;
  nlohmann::json top = nlohmann::json::array();
  for (const LcdHypothesis& h : r.lcd_top) {
    top.push_back({{"node", h.node}, {"posterior", h.posterior}, {"likelihood", h.adjusted_likelihood}});
  }
  j["lcd_top"] = top;
  j["candidates_tried"] = r.candidates_tried;
  nlohmann::json attempts = nlohmann::json::array();
  for (const CandidateAttempt& a : r.attempts) {
    attempts.push_back({{"node", a.node},
                        {"session", a.session},
                        {"source", LinkTypeName(a.source)},
                        {"status", RegistrationStatusName(a.status)},
                        {"matches", a.matches},
                        {"inliers", a.inliers},
                        {"truth_distance_m", Optional(a.truth_distance_m)},
                        {"truth_angle_deg", Optional(a.truth_angle_deg)}});
  }
  j["attempts"] = attempts;
  j["proximity_candidates"] = r.proximity_candidates;
  j["matched_node"] = r.relocalized ? nlohmann::json(r.matched_node) : nlohmann::json(nullptr);
  j["matched_session"] =
      r.relocalized ? nlohmann::json(r.matched_session) : nlohmann::json(nullptr);
  j["matched_by"] = r.relocalized ? nlohmann::json(LinkTypeName(r.matched_by)) : nlohmann::json(nullptr);
  j["inliers"] = r.inliers;
  j["cache_validation"] = r.cache_validation
                             ? nlohmann::json(CacheValidationName(*r.cache_validation))
                             : nlohmann::json(nullptr);
  j["features"] = r.num_features;
  j["jump_mm"] = Optional(r.jump_mm);
  j["pose"] = r.map_from_camera ? PoseToJson(*r.map_from_camera) : nlohmann::json(nullptr);
  j["distance_since_last_m"] = r.distance_since_last_m;
  j["timings_ms"] = {{"features", r.timings.features_ms},
                     {"lcd", r.timings.lcd_ms},
                     {"proximity", r.timings.proximity_ms},
                     {"registration", r.timings.registration_ms},
                     {"total", r.timings.total_ms}};
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

nlohmann::json MappingResultToJson(const MappingFrameResult& r) {
  return {{"node", r.node},
          {"session", r.session},
          {"features", r.num_features},
          {"lcd_status", LcdStatusName(r.lcd_status)},
          {"lcd_hypothesis", r.lcd_hypothesis},
          {"registrations", r.registrations},
          {"loop_closures_added", r.loop_closures_added},
          {"proximity_links_added", r.proximity_links_added},
          {"optimization", r.optimized ? OptimizationStatusName(r.optimization_status) : "none"},
          {"links_rejected", r.links_rejected},
          {"nodes_reduced", r.nodes_reduced},
          {"timings_ms",
           {{"features", r.timings.features_ms},
            {"lcd", r.timings.lcd_ms},
            {"proximity", r.timings.proximity_ms},
            {"registration", r.timings.registration_ms},
            {"optimization", r.timings.optimization_ms},
            {"reduction", r.timings.reduction_ms},
            {"total", r.timings.total_ms}}}};
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
