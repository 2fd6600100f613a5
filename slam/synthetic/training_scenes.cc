#include "slam/synthetic/training_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/synthetic/light/solar.h"
#include "slam/synthetic/sensor/route.h"
#include "slam/synthetic/training_furniture.h"

namespace duskmap {
namespace {

// The sub-streams of a scene's seed.
enum Stream : uint64_t { kGenerator = 1, kFurniture, kPhotos, kClock, kLamps, kPaint };

std::string ClockText(double hours) {
  const int minutes = std::clamp(static_cast<int>(std::lround(hours * 60.0)), 0, 23 * 60 + 59);
  char text[8];
  std::snprintf(text, sizeof(text), "%02d:%02d", minutes / 60, minutes % 60);
  return text;
}

// The generator seed: derived from the scene's, again while it or the
// texture seed it gives (the generator's DeriveSeed(seed, 1)) is the
// default dataset's.
uint64_t GeneratorSeed(uint64_t scene_seed) {
  const GeneratorConfig defaults;
  const uint64_t default_texture_seed = DeriveSeed(defaults.seed, 1);
  uint64_t seed = DeriveSeed(scene_seed, kGenerator);
  for (uint64_t again = 1;; ++again) {
    const uint64_t texture = DeriveSeed(seed, 1);
    if (seed != defaults.seed && texture != defaults.scene.seed && texture != default_texture_seed) return seed;
    seed = DeriveSeed(scene_seed, kGenerator + 0x100 * again);
  }
}

// Catalog photos that fit each surface class (BlendSwap-CC-0.sh3f).
const std::vector<std::pair<std::string, std::vector<std::string>>>& PhotoChoices() {
  static const std::vector<std::string> kWood = {
      "blendswap-cc-0/table/Wood_013_COLOR.jpg",       "blendswap-cc-0/lowerCabinet/american_oak.jpg",
      "blendswap-cc-0/oakTable/oak.jpg",               "blendswap-cc-0/bookcase/wood11.jpg",
      "blendswap-cc-0/bedWithTexture/wood10.jpg",      "blendswap-cc-0/televisionCabinet/wood9.jpg",
      "blendswap-cc-0/speaker3/wood12.jpg",            "blendswap-cc-0/woodToy/ash.jpg",
      "blendswap-cc-0/woodToy/mahagoni.jpg",           "blendswap-cc-0/antiqueChair/cherry.jpg",
      "blendswap-cc-0/deckChair/BEuropean_Beech.jpg",  "blendswap-cc-0/chair/wood.jpg"};
  static const std::vector<std::string> kStone = {
      "blendswap-cc-0/lowerCabinet/marble_14.jpg", "blendswap-cc-0/stoneLantern/1K-cave_rock_1-diffuse.jpg",
      "blendswap-cc-0/rock1/rock01.jpg",           "blendswap-cc-0/rock2/rock02.jpg",
      "blendswap-cc-0/rock3/rock03.jpg",           "blendswap-cc-0/plantie/ground.jpg"};
  static const std::vector<std::string> kCounter = {
      "blendswap-cc-0/lowerCabinet/marble_14.jpg", "blendswap-cc-0/rock2/rock02.jpg",
      "blendswap-cc-0/rangeHood/Metal009_2K_Color.jpg", "blendswap-cc-0/table/Wood_013_COLOR.jpg",
      "blendswap-cc-0/oakTable/oak.jpg"};
  static const std::vector<std::string> kFabric = {
      "blendswap-cc-0/chair/tecido.jpg",       "blendswap-cc-0/chairWithCushion/Denim_001_COLOR.jpg",
      "blendswap-cc-0/couch/Plain001.jpg",     "blendswap-cc-0/couch2/Fabric_011_COLOR.jpg",
      "blendswap-cc-0/chair2/NY_Chaise_Red.jpg", "blendswap-cc-0/deckChair/BlueWhite_Stripes.jpg",
      "blendswap-cc-0/tableWithTablecloth/red_checked.jpg"};
  static const std::vector<std::pair<std::string, std::vector<std::string>>> kChoices = {
      {"wood_floor", kWood}, {"tiles", kStone}, {"counter", kCounter}, {"wood", kWood}, {"fabric", kFabric}};
  return kChoices;
}

// Three scenes in five keep every surface procedural; the others draw a
// photo, at a plausible width, for each surface class with probability 1/2
// (at least one).
std::vector<PhotoMaterialSpec> DrawPhotoMaterials(uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PhotoMaterialSpec> specs;
  if (unit(rng) < 0.4) return specs;
  const auto& choices = PhotoChoices();
  const size_t forced = std::uniform_int_distribution<size_t>(0, choices.size() - 1)(rng);
  for (size_t i = 0; i < choices.size(); ++i) {
    const bool take = unit(rng) < 0.5;
    const auto& images = choices[i].second;
    PhotoMaterialSpec spec;
    spec.surface = choices[i].first;
    spec.image = images[std::uniform_int_distribution<size_t>(0, images.size() - 1)(rng)];
    spec.width_m = spec.surface == "fabric" ? 0.2 + 0.3 * unit(rng) : 0.35 + 0.45 * unit(rng);
    if (take || i == forced) specs.push_back(spec);
  }
  return specs;
}

// The sessions "1".."N": one in full day (10:00-15:00), one at lamp-lit
// night (from 75 minutes after sunset to 23:00), the others spread from two
// hours before sunset to an hour after it.
std::vector<SessionSpec> DrawSessions(int count, double sunset_h, uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double day = std::min(10.0 + 5.0 * unit(rng), sunset_h - 2.5);
  const double night_from = std::min(sunset_h + 1.25, 22.75);
  const double night = night_from + (23.0 - night_from) * unit(rng);
  const double lo = std::max(day + 0.5, sunset_h - 2.0), hi = std::min(sunset_h + 1.0, night - 0.5);
  std::vector<double> hours = {day};
  const int between = count - 2;
  for (int k = 0; k < between; ++k) hours.push_back(lo + (hi - lo) * (k + 0.15 + 0.7 * unit(rng)) / between);
  hours.push_back(night);
  std::vector<SessionSpec> sessions;
  int last_minute = -1;
  for (size_t i = 0; i < hours.size(); ++i) {
    const int minute = std::max(static_cast<int>(std::lround(hours[i] * 60.0)), last_minute + 1);
    last_minute = minute;
    sessions.push_back({std::to_string(i + 1), ClockText(minute / 60.0), "mapping"});
  }
  return sessions;
}

// The floor lamp goes on from 45 minutes before to 30 after sunset; each
// ceiling light is on in half the scenes; the lamps' colour 2500-3500 K.
void DrawLamps(double sunset_h, uint64_t seed, LampOptions* lamps) {
  Rng rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  lamps->living_lamp_on_from = ClockText(sunset_h - 0.75 + 1.25 * unit(rng));
  const bool bedroom = unit(rng) < 0.5, living = unit(rng) < 0.5;
  const double bedroom_cd = 50.0 + 40.0 * unit(rng), living_cd = 60.0 + 40.0 * unit(rng);
  lamps->bedroom_ceiling_cd = bedroom ? bedroom_cd : 0.0;
  lamps->living_ceiling_cd = living ? living_cd : 0.0;
  lamps->light.color_temperature_k = 2500.0 + 1000.0 * unit(rng);
}

// The frame rate at which the first `frames` frames of even the fastest
// session (speed factor 1 + speed_variation) span the whole patrol route.
double RouteFrameRateHz(const RouteOptions& route, int frames) {
  RouteOptions nominal = route;
  nominal.frame_rate_hz = 1.0;
  nominal.speed_variation = 0.0;
  const double duration_s = GenerateRoute(nominal, ApartmentPatrolRoute(), 0).back().time_s;
  const double rate = 1.02 * (1.0 + route.speed_variation) * (frames - 1) / duration_s;
  return std::min(rate, 60.0);
}

}  // namespace

void TrainingScenesOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, seed != 0) << "seed: must not be 0";
  SLAM_THROW_IF_NOT(ConfigError, scenes >= 1 && scenes <= 1000) << "scenes: must be in [1, 1000], got " << scenes;
  SLAM_THROW_IF_NOT(ConfigError, hours_per_scene >= 2 && hours_per_scene <= 12)
      << "hours_per_scene: must be in [2, 12], got " << hours_per_scene;
  SLAM_THROW_IF_NOT(ConfigError, frames_per_hour >= 2 && frames_per_hour <= 1000)
      << "frames_per_hour: must be in [2, 1000], got " << frames_per_hour;
}

std::string FurnitureSignature(const FurnitureOptions& furniture) {
  std::ostringstream text;
  char line[96];
  for (const FurniturePiece& p : furniture.pieces) {
    std::snprintf(line, sizeof(line), " %.4f %.4f %.3f %.4f\n", p.position_m.x(), p.position_m.y(), p.yaw_deg,
                  p.elevation_m);
    text << p.model << " | " << p.room << " |" << line;
  }
  return text.str();
}

TrainingScene MakeTrainingScene(const TrainingScenesOptions& options, int index) {
  options.Check();
  SLAM_CHECK_MSG(index >= 0 && index < options.scenes, "training scene index out of range");
  const uint64_t scene_seed = DeriveSeed(options.seed, static_cast<uint64_t>(index));
  TrainingScene scene;
  scene.index = index;
  GeneratorConfig& config = scene.config;
  // The model the committed DuskNet was trained on (run 23's walk: the
  // training data stays reproducible); its frames sample the whole patrol
  // sparsely (metres apart), so the 1 Hz step cap does not apply.
  ApplyGeneratorModel("run23-2026-12-06", &config);
  config.route.max_step_m = 1000.0;
  config.seed = GeneratorSeed(scene_seed);
  config.scene.seed = DeriveSeed(config.seed, 1);  // what GenerateDataset gives the textures
  config.scene.wall_paint_seed = DeriveSeed(scene_seed, kPaint) | 1;
  const std::string default_signature = FurnitureSignature(GeneratorConfig().scene.furniture);
  for (uint64_t again = 0; scene.furniture_signature.empty() || scene.furniture_signature == default_signature;
       ++again) {
    config.scene.furniture.pieces = DrawTrainingFurniture(DeriveSeed(scene_seed, kFurniture + 0x100 * again));
    scene.furniture_signature = FurnitureSignature(config.scene.furniture);
  }
  config.scene.photo_materials = DrawPhotoMaterials(DeriveSeed(scene_seed, kPhotos));
  // Dates spread over the year: a golden-ratio sequence from a phase of the base seed.
  const double phase = static_cast<double>(DeriveSeed(options.seed, 0xDA7E) >> 11) * 0x1.0p-53;
  const double year_fraction = std::fmod(phase + 0.6180339887498949 * index, 1.0);
  config.lighting.site.day_of_year = 1 + std::min(364, static_cast<int>(365.0 * year_fraction));
  const double sunset_h = ComputeSunsetTime(config.lighting.site);
  config.sessions = DrawSessions(options.hours_per_scene, sunset_h, DeriveSeed(scene_seed, kClock));
  DrawLamps(sunset_h, DeriveSeed(scene_seed, kLamps), &config.scene.lamps);
  config.max_frames = options.frames_per_hour;
  config.route.frame_rate_hz = RouteFrameRateHz(config.route, options.frames_per_hour);
  return scene;
}

}  // namespace duskmap
