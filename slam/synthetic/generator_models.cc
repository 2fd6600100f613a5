#include "slam/synthetic/generator_models.h"

#include <sstream>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Each model sets every setting any model decides, so that applying one
// gives the same values whatever the config held before.

// The box apartment of 2026-12-02: box furniture, procedural materials, the
// sun through the light map, the camera without its image processor.
void Boxes20261202(const GeneratorModelParts& c) {
  c.scene.box_furniture = true;
  c.scene.furniture.pieces.clear();
  c.scene.lamps.intensity_scale = 1.6;
  c.lighting.horizon_elevation_deg = 1.5;
  c.lighting.ambient_fraction = 0.35;
  c.lighting.window_view_obstructed = false;
  c.lighting.glass_transmission = 0.75;
  c.lighting.sun_per_texel = false;
  c.lighting.mesh_sun_per_sample = false;
  c.camera.exposure.motion_blur_scale = 1.0;
  c.camera.image_processor.tone_contrast = 0.12;
  c.camera.image_processor.noise_reduction = 0.0;
  c.camera.image_processor.sharpen_amount = 0.0;
  c.camera.image_processor.sharpen_sigma_px = 1.0;
  c.camera.image_processor.sharpen_threshold_levels = 0.0;
  c.route.speed_mps = 0.55;
  c.route.paced_walk = false;
  c.route.max_step_m = 1.0;
}

// Calibration run 10: the catalog furniture in place of the boxes, lamps
// x3.2, buildings opposite that hide the sun below 14 degrees, a room's
// interreflection 0.8, a phone's steep tone curve.
void Run10(const GeneratorModelParts& c) {
  Boxes20261202(c);
  c.scene.box_furniture = false;
  c.scene.furniture.pieces = DefaultFurniturePieces();
  c.scene.lamps.intensity_scale = 3.2;
  c.lighting.horizon_elevation_deg = 14.0;
  c.lighting.ambient_fraction = 0.8;
  c.camera.image_processor.tone_contrast = 0.5;
}

// Run 14: the windows see the facades opposite and the ground.
void Run14(const GeneratorModelParts& c) {
  Run10(c);
  c.lighting.window_view_obstructed = true;
}

// Run 17: the light a real window assembly lets through.
void Run17(const GeneratorModelParts& c) {
  Run14(c);
  c.lighting.glass_transmission = 0.35;
}

// Run 22: the sun per texel; the image processor's noise reduction, then
// local contrast.
void Run22(const GeneratorModelParts& c) {
  Run17(c);
  c.lighting.sun_per_texel = true;
  c.camera.image_processor.noise_reduction = 1.5;
  c.camera.image_processor.sharpen_amount = 0.5;
  c.camera.image_processor.sharpen_sigma_px = 5.0;
  c.camera.image_processor.sharpen_threshold_levels = 2.0;
}

// Run 23: the sun per pixel where a patch's edge crosses a triangle.
void Run23(const GeneratorModelParts& c) {
  Run22(c);
  c.lighting.mesh_sun_per_sample = true;
}

// Run 24: the walker's pace from the paper's words, "the maximum distance
// between two consecutive frames taken at 1 Hz while walking at 55 cm per
// second": the walker keeps its speed along the path it walks, at a pace
// that gives the paper's 201 frames per single-session map on average.
void Run24(const GeneratorModelParts& c) {
  Run23(c);
  c.route.speed_mps = 0.38;
  c.route.paced_walk = true;
  c.route.max_step_m = 0.55;
}

struct Model {
  const char* name;
  void (*apply)(const GeneratorModelParts&);
};

constexpr Model kModels[] = {{"boxes-2026-12-02", Boxes20261202}, {"run10-2026-12-05", Run10},
                             {"run14-2026-12-06", Run14},         {"run17-2026-12-06", Run17},
                             {"run22-2026-12-06", Run22},         {"run23-2026-12-06", Run23},
                             {"run24-2026-12-07", Run24}};

}  // namespace

std::vector<std::string> GeneratorModelNames() {
  std::vector<std::string> names;
  for (const Model& m : kModels) names.push_back(m.name);
  return names;
}

void CheckGeneratorModel(const std::string& name, const std::string& where) {
  for (const Model& m : kModels) {
    if (name == m.name) return;
  }
  std::ostringstream known;
  for (const Model& m : kModels) known << (&m == kModels ? "" : ", ") << m.name;
  SLAM_THROW(ConfigError) << where << ": unknown model '" << name << "' (known: " << known.str() << ")";
}

void ApplyModelValues(const std::string& name, const GeneratorModelParts& parts, const std::string& where) {
  CheckGeneratorModel(name, where);
  for (const Model& m : kModels) {
    if (name == m.name) m.apply(parts);
  }
}

std::vector<FurniturePiece> DefaultFurniturePieces() {
  // model, room, footprint centre (m), yaw (deg), elevation (m)
  return {
      {"sofa2", "living room", Eigen::Vector2d(1.7, 4.2), 0.0, 0.0},
      {"televisionCabinet", "living room", Eigen::Vector2d(0.9, 0.36), 180.0, 0.0},
      {"bookcase", "living room", Eigen::Vector2d(5.1, 0.2), 180.0, 0.0},
      {"oakTable", "living room", Eigen::Vector2d(4.5, 2.6), 0.0, 0.0},
      {"chair", "living room", Eigen::Vector2d(4.2, 3.45), 0.0, 0.0},
      {"chair", "living room", Eigen::Vector2d(4.8, 3.45), 0.0, 0.0},
      {"chair", "living room", Eigen::Vector2d(5.4, 2.6), -90.0, 0.0},
      {"plant", "living room", Eigen::Vector2d(3.7, 0.45), 0.0, 0.0},
      {"tableWithTablecloth", "kitchen", Eigen::Vector2d(7.9, 2.1), 0.0, 0.0},
      {"chair2", "kitchen", Eigen::Vector2d(7.2, 2.1), 90.0, 0.0},
      {"chair2", "kitchen", Eigen::Vector2d(7.9, 2.75), 0.0, 0.0},
      {"coffeeBrewer", "kitchen", Eigen::Vector2d(9.75, 1.2), -90.0, 0.9},
      {"bedWithTexture", "bedroom", Eigen::Vector2d(3.4, 7.86), 0.0, 0.0},
      {"wardrobeWithSlidingDoors", "bedroom", Eigen::Vector2d(5.17, 7.2), -90.0, 0.0},
      {"shelves", "bedroom", Eigen::Vector2d(0.95, 6.21), 180.0, 0.0},
      {"headphones", "living room", Eigen::Vector2d(4.25, 2.45), 30.0, 0.741},
      {"kalender", "living room", Eigen::Vector2d(4.75, 2.25), 10.0, 0.741},
      {"littlePlant", "living room", Eigen::Vector2d(4.6, 2.85), 0.0, 0.741},
      {"speaker3", "living room", Eigen::Vector2d(1.9, 0.15), 180.0, 0.0},
      {"electricGuitar", "living room", Eigen::Vector2d(5.8, 1.3), -90.0, 0.0},
      {"basketball", "living room", Eigen::Vector2d(3.0, 3.95), 0.0, 0.0},
      {"orchids", "living room", Eigen::Vector2d(3.1, 0.25), 0.0, 0.0},
      {"kitchenaid", "kitchen", Eigen::Vector2d(9.72, 2.0), -90.0, 0.9},
      {"bread", "kitchen", Eigen::Vector2d(9.7, 2.7), -80.0, 0.9},
      {"knifeStandSwap", "kitchen", Eigen::Vector2d(9.9, 3.2), -90.0, 0.9},
      {"tetrapak", "kitchen", Eigen::Vector2d(7.7, 2.0), 20.0, 0.75},
      {"yogurtBottle", "kitchen", Eigen::Vector2d(8.1, 2.25), 0.0, 0.75},
      {"plasticCup", "kitchen", Eigen::Vector2d(7.95, 1.8), 0.0, 0.75},
      {"umbrellaFolded", "corridor", Eigen::Vector2d(8.85, 5.68), 0.0, 0.0},
      {"bootie", "corridor", Eigen::Vector2d(8.4, 5.72), 10.0, 0.0},
      {"slippers", "corridor", Eigen::Vector2d(1.5, 5.72), -5.0, 0.0},
      {"handbag", "corridor", Eigen::Vector2d(6.35, 4.86), 180.0, 0.8},
      {"cuckooClock", "corridor", Eigen::Vector2d(4.0, 5.81), 0.0, 1.45},
      {"bedsideTable2", "bedroom", Eigen::Vector2d(2.1, 8.7), 180.0, 0.0},
      {"desklamp", "bedroom", Eigen::Vector2d(2.1, 8.75), 0.0, 0.454},
      {"teddyBear", "bedroom", Eigen::Vector2d(0.8, 6.2), 180.0, 0.79},
      {"caballito", "bedroom", Eigen::Vector2d(1.0, 8.3), 60.0, 0.0},
      {"slippers", "bedroom", Eigen::Vector2d(2.0, 7.3), 80.0, 0.0},
  };
}

}  // namespace duskmap
