#include "slam/synthetic/generator_config.h"

#include <set>

#include "slam/core/check.h"
#include "slam/synthetic/generator_config_json.h"

namespace duskmap {

std::vector<SessionSpec> GeneratorConfig::DefaultSessions() {
  return {{"1", "16:46", "mapping"},      {"2", "17:27", "mapping"},      {"3", "17:54", "mapping"},
          {"4", "18:27", "mapping"},      {"5", "18:56", "mapping"},      {"6", "19:35", "mapping"},
          {"A", "16:51", "localization"}, {"B", "17:31", "localization"}, {"C", "17:58", "localization"},
          {"D", "18:30", "localization"}, {"E", "18:59", "localization"}, {"F", "19:42", "localization"}};
}

void GeneratorConfig::Check() const {
  CheckGeneratorModel(model, "model");
  SLAM_THROW_IF_NOT(ConfigError, threads >= 1 && threads <= 64) << "threads must be in [1, 64], got " << threads;
  SLAM_THROW_IF_NOT(ConfigError, max_frames >= 0) << "max_frames must be >= 0, got " << max_frames;
  scene.Check();
  lighting.Check();
  camera.Check();
  depth.Check();
  route.Check();
  odometry.Check();
  SLAM_THROW_IF_NOT(ConfigError, !lighting.window_view_in_camera ||
                                     (scene.window_reflectance == 0.0 && scene.floor_reflectance == 0.0))
      << "lighting.window_view_in_camera does not support mirrors (scene.window_reflectance and "
         "scene.floor_reflectance must be 0)";
  SLAM_THROW_IF_NOT(ConfigError, !sessions.empty()) << "sessions must not be empty";
  std::set<std::string> names;
  for (const SessionSpec& s : sessions) {
    const bool name_ok = !s.name.empty() && s.name.find_first_of("/\\. ") == std::string::npos;
    SLAM_THROW_IF_NOT(ConfigError, name_ok) << "sessions: invalid session name '" << s.name << "'";
    SLAM_THROW_IF_NOT(ConfigError, names.insert(s.name).second) << "sessions: duplicate session name '" << s.name << "'";
    ParseClockTime(s.clock_time, "sessions." + s.name + ".clock_time");
    SLAM_THROW_IF_NOT(ConfigError, s.day >= 0 && s.day <= 365)
        << "sessions." << s.name << ".day must be in [0, 365], got " << s.day;
    SLAM_THROW_IF_NOT(ConfigError, s.role == "mapping" || s.role == "localization")
        << "sessions." << s.name << ".role must be \"mapping\" or \"localization\", got \"" << s.role << "\"";
  }
}

void ApplyGeneratorModel(const std::string& name, GeneratorConfig* config, const std::string& where) {
  ApplyModelValues(name, {config->scene, config->lighting, config->camera, config->route}, where);
  config->model = name;
}

std::vector<std::pair<std::string, std::string>> MovedGeneratorKeys() {
  return {{"camera.ae_target", "camera.exposure.target"},
          {"camera.ae_speed", "camera.exposure.speed"},
          {"camera.min_exposure_s", "camera.exposure.min_time_s"},
          {"camera.max_exposure_s", "camera.exposure.max_time_s"},
          {"camera.max_gain", "camera.exposure.max_gain"},
          {"camera.sensitivity", "camera.exposure.sensitivity"},
          {"camera.motion_blur_scale", "camera.exposure.motion_blur_scale"},
          {"camera.awb_speed", "camera.white_balance.speed"},
          {"camera.awb_strength", "camera.white_balance.strength"},
          {"camera.photons_at_white", "camera.noise.photons_at_white"},
          {"camera.read_noise", "camera.noise.read_noise"},
          {"camera.gamma", "camera.image_processor.gamma"},
          {"camera.tone_contrast", "camera.image_processor.tone_contrast"},
          {"camera.noise_reduction", "camera.image_processor.noise_reduction"},
          {"camera.noise_reduction_sigma_px", "camera.image_processor.noise_reduction_sigma_px"},
          {"camera.sharpen_amount", "camera.image_processor.sharpen_amount"},
          {"camera.sharpen_sigma_px", "camera.image_processor.sharpen_sigma_px"},
          {"camera.sharpen_threshold_levels", "camera.image_processor.sharpen_threshold_levels"},
          {"scene.lamp_intensity_scale", "scene.lamps.intensity_scale"},
          {"scene.living_lamp_on_from", "scene.lamps.living_lamp_on_from"},
          {"scene.bedroom_ceiling_cd", "scene.lamps.bedroom_ceiling_cd"},
          {"scene.living_ceiling_cd", "scene.lamps.living_ceiling_cd"},
          {"lighting.lamp_color_temperature_k", "scene.lamps.color_temperature_k"},
          {"lighting.lamp_shade_nits_per_cd", "scene.lamps.shade_nits_per_cd"}};
}

namespace {

// A moved key (MovedGeneratorKeys: "object.key") in the file is refused with
// its new path.
void RejectMovedKeys(const nlohmann::json& json, const std::string& path) {
  if (!json.is_object()) return;
  for (const auto& [old_path, new_path] : MovedGeneratorKeys()) {
    const size_t dot = old_path.find('.');
    const auto object = json.find(old_path.substr(0, dot));
    if (object == json.end() || !object->is_object() || !object->contains(old_path.substr(dot + 1))) continue;
    SLAM_THROW(ConfigError) << path << "." << old_path << ": moved to " << new_path;
  }
}

}  // namespace

GeneratorConfig ReadGeneratorConfig(const std::string& path) {
  const nlohmann::json json = ReadJsonFile(path);
  RejectMovedKeys(json, path);
  JsonFields fields(json, path);
  std::string model = kDefaultGeneratorModel;
  fields.Read("model", &model);
  GeneratorConfig config;
  ApplyGeneratorModel(model, &config, path + ".model");
  JsonCodecReader::ReadFields(fields, &config);
  try {
    config.Check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << path << ": " << e.what();
  }
  return config;
}

}  // namespace duskmap
