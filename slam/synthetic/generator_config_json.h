// JSON codecs of the dataset generator's configuration
// (configs/sunset_apartment.json; slam/core/json_codec.h): one field list per
// building block's options, composed by GeneratorConfig's. Every key is optional: the
// file's "model" (generator_models.h; absent: the default model) gives the
// values it does not set (ReadGeneratorConfig).
//   {"model": "run23-2026-12-06", "seed": 2024, "threads": 2, "max_frames": 0,
//    "scene": {"wall_height_m": 2.5, ..., "lamps": {"intensity_scale": 3.2, ...}, "furniture": {"catalog": "", "max_edge_m": 0.12,
//              "pieces": [{"model": "bed1", "room": "bedroom", "position_m": [x, y]}]}},
//    "lighting": {"latitude_deg": 45.4, ...}, "camera": {...}, "depth": {...},
//    "route": {...}, "odometry": {...},
//    "sessions": [{"name": "1", "clock_time": "16:46", "role": "mapping"}, ...]}
// The scene's texture seed is derived from the top-level seed, so a config
// cannot set scene.seed.
#pragma once

#include "slam/core/json_codec.h"
#include "slam/synthetic/generator_config.h"

namespace duskmap {

template <>
struct JsonCodec<FurniturePiece> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("model", o.model, JsonRequired{});
    f("room", o.room, JsonRequired{});
    f("position_m", o.position_m, JsonRequired{});
    f("yaw_deg", o.yaw_deg);
    f("elevation_m", o.elevation_m);
  }
};

template <>
struct JsonCodec<PhotoMaterialSpec> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("surface", o.surface, JsonRequired{});
    f("image", o.image, JsonRequired{});
    f("width_m", o.width_m);
    f("texel_m", o.texel_m);
  }
};

template <>
struct JsonCodec<FurnitureOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("catalog", o.catalog);
    f("max_edge_m", o.max_edge_m);
    f("pieces", o.pieces);
  }
};

// Every lamp knob; the light's keys sit in the lamps object itself.
template <>
struct JsonCodec<LampOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("intensity_scale", o.intensity_scale);
    f("living_lamp_on_from", o.living_lamp_on_from);
    f("bedroom_ceiling_cd", o.bedroom_ceiling_cd);
    f("living_ceiling_cd", o.living_ceiling_cd);
    f("color_temperature_k", o.light.color_temperature_k);
    f("shade_nits_per_cd", o.light.shade_nits_per_cd);
  }
};

template <>
struct JsonCodec<ApartmentOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("seed", o.seed);
    f("textures_dir", o.textures_dir);
    f("wall_height_m", o.wall_height_m);
    f("lamps", o.lamps);
    f("window_reflectance", o.window_reflectance);
    f("floor_reflectance", o.floor_reflectance);
    f("relief_scale", o.relief_scale);
    f("wall_paint_seed", o.wall_paint_seed);
    f("box_furniture", o.box_furniture);
    f("furniture", o.furniture);
    f("photo_materials", o.photo_materials);
  }
};

// The site's keys sit in the lighting object itself.
template <>
struct JsonCodec<LightingOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("latitude_deg", o.site.latitude_deg);
    f("longitude_deg", o.site.longitude_deg);
    f("utc_offset_h", o.site.utc_offset_h);
    f("day_of_year", o.site.day_of_year);
    f("sun_illuminance_lux", o.sun_illuminance_lux);
    f("optical_depth_bgr", o.optical_depth_bgr);
    f("horizon_elevation_deg", o.horizon_elevation_deg);
    f("sky_log10_lux_knots", o.sky_log10_lux_knots);
    f("glass_transmission", o.glass_transmission);
    f("window_view_obstructed", o.window_view_obstructed);
    f("window_view_in_camera", o.window_view_in_camera);
    f("facade_reflectance", o.facade_reflectance);
    f("ground_reflectance", o.ground_reflectance);
    f("ambient_fraction", o.ambient_fraction);
    f("ambient_leak", o.ambient_leak);
    f("light_texel_m", o.light_texel_m);
    f("sun_per_texel", o.sun_per_texel);
    f("mesh_sun_per_sample", o.mesh_sun_per_sample);
    f("mesh_sun_sample_m", o.mesh_sun_sample_m);
  }
};

template <>
struct JsonCodec<CameraExposureOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("target", o.target);
    f("speed", o.speed);
    f("min_time_s", o.min_time_s);
    f("max_time_s", o.max_time_s);
    f("max_gain", o.max_gain);
    f("sensitivity", o.sensitivity);
    f("motion_blur_scale", o.motion_blur_scale);
  }
};

template <>
struct JsonCodec<WhiteBalanceOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("speed", o.speed);
    f("strength", o.strength);
  }
};

template <>
struct JsonCodec<CameraNoiseOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("photons_at_white", o.photons_at_white);
    f("read_noise", o.read_noise);
  }
};

template <>
struct JsonCodec<ImageProcessorOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("gamma", o.gamma);
    f("tone_contrast", o.tone_contrast);
    f("noise_reduction", o.noise_reduction);
    f("noise_reduction_sigma_px", o.noise_reduction_sigma_px);
    f("sharpen_amount", o.sharpen_amount);
    f("sharpen_sigma_px", o.sharpen_sigma_px);
    f("sharpen_threshold_levels", o.sharpen_threshold_levels);
  }
};

// "camera": {"width": 640, "height": 480, "fx": 525, "fy": 525, "blur_sigma_px": 0.6,
//            "exposure": {...}, "white_balance": {...}, "noise": {...}, "image_processor": {...}}
// (the flat keys before issue 45 are refused with their new key: MovedGeneratorKeys()).
template <>
struct JsonCodec<CameraModelOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("width", o.width);
    f("height", o.height);
    f("fx", o.fx);
    f("fy", o.fy);
    f("blur_sigma_px", o.blur_sigma_px);
    f("exposure", o.exposure);
    f("white_balance", o.white_balance);
    f("noise", o.noise);
    f("image_processor", o.image_processor);
  }
};

template <>
struct JsonCodec<DepthSensorOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("min_range_m", o.min_range_m);
    f("max_range_m", o.max_range_m);
    f("noise_base_m", o.noise_base_m);
    f("noise_quadratic", o.noise_quadratic);
    f("min_cos_incidence", o.min_cos_incidence);
    f("dropout_probability", o.dropout_probability);
    f("edge_dropout_probability", o.edge_dropout_probability);
    f("edge_jump_m", o.edge_jump_m);
  }
};

template <>
struct JsonCodec<RouteOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("speed_mps", o.speed_mps);
    f("turn_speed_dps", o.turn_speed_dps);
    f("corner_turn_speed_dps", o.corner_turn_speed_dps);
    f("frame_rate_hz", o.frame_rate_hz);
    f("height_m", o.height_m);
    f("height_spread_m", o.height_spread_m);
    f("lateral_max_m", o.lateral_max_m);
    f("heading_max_deg", o.heading_max_deg);
    f("speed_variation", o.speed_variation);
    f("sway_deg", o.sway_deg);
    f("bob_m", o.bob_m);
    f("pitch_deg", o.pitch_deg);
    f("max_step_m", o.max_step_m);
    f("paced_walk", o.paced_walk);
  }
};

template <>
struct JsonCodec<OdometryOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("drift_fraction", o.drift_fraction);
    f("scale_error_std", o.scale_error_std);
    f("yaw_drift_deg_per_min", o.yaw_drift_deg_per_min);
    f("yaw_noise_fraction", o.yaw_noise_fraction);
  }
};

template <>
struct JsonCodec<SessionSpec> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("name", o.name, JsonRequired{});
    f("clock_time", o.clock_time, JsonRequired{});
    f("role", o.role);
    f("day", o.day);
  }
};

template <>
struct JsonCodec<GeneratorConfig> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("model", o.model);
    f("seed", o.seed);
    f("threads", o.threads);
    f("max_frames", o.max_frames);
    f("scene", o.scene, {{"seed", "seed"}});
    f("lighting", o.lighting);
    f("camera", o.camera);
    f("depth", o.depth);
    f("route", o.route);
    f("odometry", o.odometry);
    f("sessions", o.sessions);
  }
};

}  // namespace duskmap
