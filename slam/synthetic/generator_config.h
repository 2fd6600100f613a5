// The configuration of `duskmap generate`: every model constant, the sessions
// and the seeds. Its defaults are the default dataset (the default model,
// generator_models.h); a config file selects a model with "model" and sets
// what differs from it. Read strictly: an unknown key anywhere is a
// ConfigError naming it.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "slam/synthetic/generator_models.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/sensor/camera_model.h"
#include "slam/synthetic/sensor/depth_sensor.h"
#include "slam/synthetic/sensor/odometry.h"
#include "slam/synthetic/sensor/route.h"

namespace duskmap {

struct SessionSpec {
  std::string name;        // "1".."6", "A".."F"
  std::string clock_time;  // local "HH:MM"
  std::string role = "mapping";  // "mapping" or "localization"
  // Days after lighting.day_of_year, [0, 365]: the session's date, whose
  // sun's path lights it (past the year's end, the next year's; lamps keep
  // their clock-time schedule) and whose first frame is at day * 86400 s +
  // the clock time (SessionStartTimestamp). 0: lighting.day_of_year itself.
  int day = 0;
};

struct GeneratorConfig;

// Sets the values model `name` decides (generator_models.h) on `config`, and
// config->model; throws ConfigError "<where>: unknown model ..." naming the
// known ones.
void ApplyGeneratorModel(const std::string& name, GeneratorConfig* config, const std::string& where = "model");

// The building blocks' options (ApartmentOptions, LightingOptions,
// CameraModelOptions, ...) default to their features off, which their unit
// tests use; GeneratorConfig's constructor sets the default model on them.
struct GeneratorConfig {
  GeneratorConfig() { ApplyGeneratorModel(kDefaultGeneratorModel, this); }

  std::string model;     // the model these values started from (generator_models.h)
  uint64_t seed = 2024;  // base seed of everything (textures, routes, noise)
  int threads = 2;       // sessions generated in parallel (output is identical)
  int max_frames = 0;    // 0 = the whole route; otherwise the first N frames (tests)
  ApartmentOptions scene;
  LightingOptions lighting;
  CameraModelOptions camera;
  DepthSensorOptions depth;
  RouteOptions route;
  OdometryOptions odometry;
  std::vector<SessionSpec> sessions = DefaultSessions();

  // The paper's sessions: mapping 1-6 at 16:46 ... 19:35, localization A-F at
  // 16:51 ... 19:42.
  static std::vector<SessionSpec> DefaultSessions();
  void Check() const;
};

// The config keys that moved (issue 45: the camera's flat keys into its
// stages, the lamps' keys of scene and lighting into scene.lamps), old
// dotted path -> new one. A file that still has one is refused
// with its new key: "<path>.camera.ae_target: moved to camera.exposure.target".
std::vector<std::pair<std::string, std::string>> MovedGeneratorKeys();

// Reads a config file: its "model" (absent: the default model), then every
// other key over that model's values. Throws ConfigError "<path>.<key>: <problem>".
GeneratorConfig ReadGeneratorConfig(const std::string& path);

}  // namespace duskmap
