#include "slam/synthetic/generator_config.h"

#include <array>
#include <set>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"

namespace duskmap {
namespace {

void ReadFurniture(JsonFields f, FurnitureOptions* o) {
  f.Read("catalog", &o->catalog);
  f.Read("max_edge_m", &o->max_edge_m);
  if (f.Has("pieces")) {
    const nlohmann::json& pieces = f.Raw("pieces");
    const std::string where = f.where() + ".pieces";
    SLAM_THROW_IF_NOT(ConfigError, pieces.is_array())
        << where << ": wrong type (" << pieces.type_name() << ", expected an array)";
    o->pieces.clear();
    for (size_t i = 0; i < pieces.size(); ++i) {
      const std::string item = where + "[" + std::to_string(i) + "]";
      SLAM_THROW_IF_NOT(ConfigError, pieces[i].is_object())
          << item << ": wrong type (" << pieces[i].type_name() << ", expected an object)";
      JsonFields p(pieces[i], item);
      FurniturePiece piece;
      p.ReadRequired("model", &piece.model);
      p.ReadRequired("room", &piece.room);
      std::array<double, 2> xy = {0.0, 0.0};
      p.ReadRequired("position_m", &xy);
      piece.position_m = Eigen::Vector2d(xy[0], xy[1]);
      p.Read("yaw_deg", &piece.yaw_deg);
      p.Read("elevation_m", &piece.elevation_m);
      p.RejectUnknown();
      o->pieces.push_back(piece);
    }
  }
  f.RejectUnknown();
}

void ReadScene(JsonFields f, ApartmentOptions* o) {
  f.Read("textures_dir", &o->textures_dir);
  f.Read("wall_height_m", &o->wall_height_m);
  f.Read("lamp_intensity_scale", &o->lamp_intensity_scale);
  f.Read("living_lamp_on_from", &o->living_lamp_on_from);
  f.Read("bedroom_ceiling_cd", &o->bedroom_ceiling_cd);
  f.Read("living_ceiling_cd", &o->living_ceiling_cd);
  f.Read("window_reflectance", &o->window_reflectance);
  f.Read("floor_reflectance", &o->floor_reflectance);
  f.Read("relief_scale", &o->relief_scale);
  f.Read("box_furniture", &o->box_furniture);
  if (f.Has("furniture")) ReadFurniture(f.Child("furniture"), &o->furniture);
  f.RejectUnknown();
}

void ReadLighting(JsonFields f, LightingOptions* o) {
  f.Read("latitude_deg", &o->site.latitude_deg);
  f.Read("longitude_deg", &o->site.longitude_deg);
  f.Read("utc_offset_h", &o->site.utc_offset_h);
  f.Read("day_of_year", &o->site.day_of_year);
  f.Read("sun_illuminance_lux", &o->sun_illuminance_lux);
  f.Read("optical_depth_bgr", &o->optical_depth_bgr);
  f.Read("horizon_elevation_deg", &o->horizon_elevation_deg);
  f.Read("sky_log10_lux_knots", &o->sky_log10_lux_knots);
  f.Read("glass_transmission", &o->glass_transmission);
  f.Read("lamp_color_temperature_k", &o->lamp_color_temperature_k);
  f.Read("lamp_shade_nits_per_cd", &o->lamp_shade_nits_per_cd);
  f.Read("ambient_fraction", &o->ambient_fraction);
  f.Read("ambient_leak", &o->ambient_leak);
  f.Read("light_texel_m", &o->light_texel_m);
  f.RejectUnknown();
}

void ReadCamera(JsonFields f, CameraModelOptions* o) {
  f.Read("width", &o->width);
  f.Read("height", &o->height);
  f.Read("fx", &o->fx);
  f.Read("fy", &o->fy);
  f.Read("ae_target", &o->ae_target);
  f.Read("ae_speed", &o->ae_speed);
  f.Read("min_exposure_s", &o->min_exposure_s);
  f.Read("max_exposure_s", &o->max_exposure_s);
  f.Read("max_gain", &o->max_gain);
  f.Read("sensitivity", &o->sensitivity);
  f.Read("awb_speed", &o->awb_speed);
  f.Read("awb_strength", &o->awb_strength);
  f.Read("photons_at_white", &o->photons_at_white);
  f.Read("read_noise", &o->read_noise);
  f.Read("blur_sigma_px", &o->blur_sigma_px);
  f.Read("gamma", &o->gamma);
  f.Read("tone_contrast", &o->tone_contrast);
  f.Read("motion_blur_scale", &o->motion_blur_scale);
  f.Read("sharpen_amount", &o->sharpen_amount);
  f.Read("sharpen_sigma_px", &o->sharpen_sigma_px);
  f.Read("sharpen_threshold_levels", &o->sharpen_threshold_levels);
  f.RejectUnknown();
}

void ReadDepth(JsonFields f, DepthSensorOptions* o) {
  f.Read("min_range_m", &o->min_range_m);
  f.Read("max_range_m", &o->max_range_m);
  f.Read("noise_base_m", &o->noise_base_m);
  f.Read("noise_quadratic", &o->noise_quadratic);
  f.Read("min_cos_incidence", &o->min_cos_incidence);
  f.Read("dropout_probability", &o->dropout_probability);
  f.Read("edge_dropout_probability", &o->edge_dropout_probability);
  f.Read("edge_jump_m", &o->edge_jump_m);
  f.RejectUnknown();
}

void ReadRoute(JsonFields f, RouteOptions* o) {
  f.Read("speed_mps", &o->speed_mps);
  f.Read("turn_speed_dps", &o->turn_speed_dps);
  f.Read("corner_turn_speed_dps", &o->corner_turn_speed_dps);
  f.Read("frame_rate_hz", &o->frame_rate_hz);
  f.Read("height_m", &o->height_m);
  f.Read("height_spread_m", &o->height_spread_m);
  f.Read("lateral_max_m", &o->lateral_max_m);
  f.Read("heading_max_deg", &o->heading_max_deg);
  f.Read("speed_variation", &o->speed_variation);
  f.Read("sway_deg", &o->sway_deg);
  f.Read("bob_m", &o->bob_m);
  f.Read("pitch_deg", &o->pitch_deg);
  f.RejectUnknown();
}

void ReadOdometry(JsonFields f, OdometryOptions* o) {
  f.Read("drift_fraction", &o->drift_fraction);
  f.Read("scale_error_std", &o->scale_error_std);
  f.Read("yaw_drift_deg_per_min", &o->yaw_drift_deg_per_min);
  f.Read("yaw_noise_fraction", &o->yaw_noise_fraction);
  f.RejectUnknown();
}

std::vector<SessionSpec> ReadSessions(const nlohmann::json& array, const std::string& where) {
  SLAM_THROW_IF_NOT(ConfigError, array.is_array()) << where << ": must be an array";
  std::vector<SessionSpec> sessions;
  for (size_t i = 0; i < array.size(); ++i) {
    JsonFields f(array[i], where + "[" + std::to_string(i) + "]");
    SessionSpec s;
    f.ReadRequired("name", &s.name);
    f.ReadRequired("clock_time", &s.clock_time);
    f.Read("role", &s.role);
    f.RejectUnknown();
    sessions.push_back(s);
  }
  return sessions;
}

}  // namespace

std::vector<SessionSpec> GeneratorConfig::DefaultSessions() {
  return {{"1", "16:46", "mapping"},      {"2", "17:27", "mapping"},      {"3", "17:54", "mapping"},
          {"4", "18:27", "mapping"},      {"5", "18:56", "mapping"},      {"6", "19:35", "mapping"},
          {"A", "16:51", "localization"}, {"B", "17:31", "localization"}, {"C", "17:58", "localization"},
          {"D", "18:30", "localization"}, {"E", "18:59", "localization"}, {"F", "19:42", "localization"}};
}

void GeneratorConfig::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, threads >= 1 && threads <= 64) << "threads must be in [1, 64], got " << threads;
  SLAM_THROW_IF_NOT(ConfigError, max_frames >= 0) << "max_frames must be >= 0, got " << max_frames;
  scene.Check();
  lighting.Check();
  camera.Check();
  depth.Check();
  route.Check();
  odometry.Check();
  SLAM_THROW_IF_NOT(ConfigError, !sessions.empty()) << "sessions must not be empty";
  std::set<std::string> names;
  for (const SessionSpec& s : sessions) {
    const bool name_ok = !s.name.empty() && s.name.find_first_of("/\\. ") == std::string::npos;
    SLAM_THROW_IF_NOT(ConfigError, name_ok) << "sessions: invalid session name '" << s.name << "'";
    SLAM_THROW_IF_NOT(ConfigError, names.insert(s.name).second) << "sessions: duplicate session name '" << s.name << "'";
    ParseClockTime(s.clock_time, "sessions." + s.name + ".clock_time");
    SLAM_THROW_IF_NOT(ConfigError, s.role == "mapping" || s.role == "localization")
        << "sessions." << s.name << ".role must be \"mapping\" or \"localization\", got \"" << s.role << "\"";
  }
}

GeneratorConfig ReadGeneratorConfig(const std::string& path) {
  GeneratorConfig config;
  JsonFields f(ReadJsonFile(path), path);
  f.Read("seed", &config.seed);
  f.Read("threads", &config.threads);
  f.Read("max_frames", &config.max_frames);
  ReadScene(f.Child("scene"), &config.scene);
  ReadLighting(f.Child("lighting"), &config.lighting);
  ReadCamera(f.Child("camera"), &config.camera);
  ReadDepth(f.Child("depth"), &config.depth);
  ReadRoute(f.Child("route"), &config.route);
  ReadOdometry(f.Child("odometry"), &config.odometry);
  if (f.Has("sessions")) config.sessions = ReadSessions(f.Raw("sessions"), path + ":sessions");
  f.RejectUnknown();
  try {
    config.Check();
  } catch (const ConfigError& e) {
    throw ConfigError(path + ": " + e.what());
  }
  return config;
}

}  // namespace duskmap
