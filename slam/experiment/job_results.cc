#include "slam/experiment/job_results.h"

#include <fstream>

#include "slam/core/check.h"

namespace duskmap {

void to_json(nlohmann::json& json, const StageTimesMs& t) {
  json = {{"features", t.features},
          {"loop_closure_detection", t.loop_closure_detection},
          {"proximity_detection", t.proximity_detection},
          {"transformation_estimation", t.transformation_estimation},
          {"optimisation", t.optimisation},
          {"total", t.total}};
}

void from_json(const nlohmann::json& json, StageTimesMs& t) {
  json.at("features").get_to(t.features);
  json.at("loop_closure_detection").get_to(t.loop_closure_detection);
  json.at("proximity_detection").get_to(t.proximity_detection);
  json.at("transformation_estimation").get_to(t.transformation_estimation);
  json.at("optimisation").get_to(t.optimisation);
  json.at("total").get_to(t.total);
}

void to_json(nlohmann::json& json, const LocalizationJobSummary& s) {
  json = {{"num_frames", s.num_frames},
          {"num_relocalized", s.num_relocalized},
          {"num_no_candidate", s.num_no_candidate},
          {"has_ground_truth", s.has_ground_truth},
          {"num_within_threshold", s.num_within_threshold},
          {"num_wrong", s.num_wrong},
          {"mean_inliers_pct", s.mean_inliers_pct},
          {"mean_jump_mm", s.mean_jump_mm},
          {"mean_features", s.mean_features},
          {"max_gap_m", s.max_gap_m},
          {"num_within_55cm", s.num_within_55cm},
          {"matched_session_per_frame", s.matched_session_per_frame},
          {"mean_times_ms", s.mean_times_ms},
          {"median_lcd_te_ms", s.median_lcd_te_ms},
          {"memory_bytes", s.memory_bytes},
          {"map_load_s", s.map_load_s},
          {"map_from_cache", s.map_from_cache},
          {"localizer_setup_s", s.localizer_setup_s},
          {"index_restore_s", s.index_restore_s},
          {"index_restored", s.index_restored},
          {"index_rebuild_reason", s.index_rebuild_reason}};
}

void from_json(const nlohmann::json& json, LocalizationJobSummary& s) {
  json.at("num_frames").get_to(s.num_frames);
  json.at("num_relocalized").get_to(s.num_relocalized);
  json.at("num_no_candidate").get_to(s.num_no_candidate);
  json.at("has_ground_truth").get_to(s.has_ground_truth);
  json.at("num_within_threshold").get_to(s.num_within_threshold);
  json.at("num_wrong").get_to(s.num_wrong);
  json.at("mean_inliers_pct").get_to(s.mean_inliers_pct);
  json.at("mean_jump_mm").get_to(s.mean_jump_mm);
  json.at("mean_features").get_to(s.mean_features);
  json.at("max_gap_m").get_to(s.max_gap_m);
  json.at("num_within_55cm").get_to(s.num_within_55cm);
  json.at("matched_session_per_frame").get_to(s.matched_session_per_frame);
  json.at("mean_times_ms").get_to(s.mean_times_ms);
  json.at("median_lcd_te_ms").get_to(s.median_lcd_te_ms);
  json.at("memory_bytes").get_to(s.memory_bytes);
  s.map_load_s = json.value("map_load_s", 0.0);
  s.map_from_cache = json.value("map_from_cache", false);
  s.localizer_setup_s = json.value("localizer_setup_s", 0.0);
  s.index_restore_s = json.value("index_restore_s", 0.0);
  s.index_restored = json.value("index_restored", false);
  s.index_rebuild_reason = json.value("index_rebuild_reason", std::string());
}

void to_json(nlohmann::json& json, const MapJobSummary& s) {
  json = {{"num_nodes", s.num_nodes},
          {"nodes_per_session", s.nodes_per_session},
          {"links_per_type", s.links_per_type},
          {"num_connected_components", s.num_connected_components},
          {"vocabulary_words", s.vocabulary_words},
          {"descriptor_bytes_per_feature", s.descriptor_bytes_per_feature},
          {"memory_bytes", s.memory_bytes},
          {"ate_mm", s.ate_mm},
          {"mean_features", s.mean_features},
          {"mean_times_ms", s.mean_times_ms},
          {"build_wall_s", s.build_wall_s},
          {"index_build_s", s.index_build_s}};
}

void from_json(const nlohmann::json& json, MapJobSummary& s) {
  json.at("num_nodes").get_to(s.num_nodes);
  json.at("nodes_per_session").get_to(s.nodes_per_session);
  json.at("links_per_type").get_to(s.links_per_type);
  json.at("num_connected_components").get_to(s.num_connected_components);
  json.at("vocabulary_words").get_to(s.vocabulary_words);
  json.at("descriptor_bytes_per_feature").get_to(s.descriptor_bytes_per_feature);
  json.at("memory_bytes").get_to(s.memory_bytes);
  json.at("ate_mm").get_to(s.ate_mm);
  json.at("mean_features").get_to(s.mean_features);
  json.at("mean_times_ms").get_to(s.mean_times_ms);
  json.at("build_wall_s").get_to(s.build_wall_s);
  s.index_build_s = json.value("index_build_s", 0.0);
}

void WriteSummary(const std::filesystem::path& job_dir, const nlohmann::json& summary) {
  const std::filesystem::path path = job_dir / "summary.json";
  std::ofstream out(path);
  out << summary.dump(1) << "\n";
  SLAM_THROW_IF_NOT(InputError, out.good()) << path.string() << ": cannot write";
}

nlohmann::json ReadSummary(const std::filesystem::path& job_dir) {
  const std::filesystem::path path = job_dir / "summary.json";
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path.string() << ": missing job summary";
  nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  SLAM_THROW_IF_NOT(InputError, !json.is_discarded())
      << path.string() << ": malformed job summary (not valid JSON)";
  return json;
}

}  // namespace duskmap
