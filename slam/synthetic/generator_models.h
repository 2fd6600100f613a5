// The dataset generator's models: named, dated value sets of the settings
// that changed from one default dataset to the next (the calibration log,
// docs/calibration_log.md). A config selects one with "model" and sets
// anything else on top; without "model" it starts from the default model,
// which is also what GeneratorConfig's constructor gives. Each model
// reproduces the bytes of the default dataset of its day.
//
//   boxes-2026-12-02   box furniture, procedural materials, the sun through
//                      the light map (configs/sunset_apartment_boxes.json)
//   run10-2026-12-05   38 catalog pieces, lamps x3.2, the sun hidden below
//                      14 degrees, interreflection 0.8, tone contrast 0.5
//   run14-2026-12-06   + the windows' view obstructed (facades, ground)
//   run17-2026-12-06   + glass transmission 0.35 (the last light-map sun)
//   run22-2026-12-06   + the sun per texel, noise reduction, local contrast
//   run23-2026-12-06   + the sun per pixel on the furniture
//   run24-2026-12-07   + the walker's pace: no step over 55 cm between 1 Hz
//                      frames, 0.38 m/s along the walked path (the default)
#pragma once

#include <string>
#include <vector>

#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/scene/furniture_layout.h"
#include "slam/synthetic/sensor/camera_model.h"
#include "slam/synthetic/sensor/route.h"

namespace duskmap {

inline constexpr const char* kDefaultGeneratorModel = "run24-2026-12-07";

// Every model's name, oldest first.
std::vector<std::string> GeneratorModelNames();

// Throws ConfigError "<where>: unknown model 'x' (known: ...)" unless `name`
// is a model's.
void CheckGeneratorModel(const std::string& name, const std::string& where);

// The options whose values a model decides (GeneratorConfig's; the config
// applies a model through ApplyGeneratorModel, generator_config.h).
struct GeneratorModelParts {
  ApartmentOptions& scene;
  LightingOptions& lighting;
  CameraModelOptions& camera;
  RouteOptions& route;
};

// Sets every value a model decides to that model's (the rest of the parts
// is left alone); throws as CheckGeneratorModel.
void ApplyModelValues(const std::string& name, const GeneratorModelParts& parts, const std::string& where);

// The furnished models' arrangement: 38 pieces of sweethome3d-furniture's
// BlendSwap catalog in the four rooms (calibration runs 6 and 10).
std::vector<FurniturePiece> DefaultFurniturePieces();

}  // namespace duskmap
