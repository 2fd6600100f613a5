#include "slam/synthetic/training_scenes.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/core/json_reader.h"
#include "slam/core/random.h"
#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/generator_config_json.h"
#include "slam/synthetic/generator_models.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/training_furniture.h"
#include "slam/synthetic/training_scenes_json.h"

namespace duskmap {
namespace {

constexpr int kManyScenes = 200;

TrainingScenesOptions Many() {
  TrainingScenesOptions options;
  options.scenes = kManyScenes;
  return options;
}

std::string ErrorOf(const TrainingScenesOptions& options) {
  try {
    options.Check();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(TrainingScenesOptions, CheckNamesTheField) {
  EXPECT_EQ(ErrorOf(TrainingScenesOptions()), "");
  TrainingScenesOptions o;
  o.seed = 0;
  EXPECT_EQ(ErrorOf(o), "seed: must not be 0");
  o = TrainingScenesOptions();
  o.scenes = 1001;
  EXPECT_EQ(ErrorOf(o), "scenes: must be in [1, 1000], got 1001");
  o.scenes = 0;
  EXPECT_EQ(ErrorOf(o), "scenes: must be in [1, 1000], got 0");
  o = TrainingScenesOptions();
  o.hours_per_scene = 1;
  EXPECT_EQ(ErrorOf(o), "hours_per_scene: must be in [2, 12], got 1");
  o.hours_per_scene = 13;
  EXPECT_EQ(ErrorOf(o), "hours_per_scene: must be in [2, 12], got 13");
  o = TrainingScenesOptions();
  o.frames_per_hour = 1;
  EXPECT_EQ(ErrorOf(o), "frames_per_hour: must be in [2, 1000], got 1");
  o.frames_per_hour = 1001;
  EXPECT_EQ(ErrorOf(o), "frames_per_hour: must be in [2, 1000], got 1001");
}

TEST(TrainingScenesOptions, JsonRoundTripAndStrictReading) {
  TrainingScenesOptions o;
  o.seed = 99;
  o.scenes = 3;
  o.hours_per_scene = 5;
  o.frames_per_hour = 7;
  const TrainingScenesOptions back = ReadJsonOptions<TrainingScenesOptions>(ToJsonObject(o), "data");
  EXPECT_EQ(back.seed, 99u);
  EXPECT_EQ(back.scenes, 3);
  EXPECT_EQ(back.hours_per_scene, 5);
  EXPECT_EQ(back.frames_per_hour, 7);
  const TrainingScenesOptions defaults = ReadJsonOptions<TrainingScenesOptions>(nlohmann::json::object(), "data");
  EXPECT_EQ(defaults.scenes, TrainingScenesOptions().scenes);
  EXPECT_THROW(ReadJsonOptions<TrainingScenesOptions>(nlohmann::json{{"scene", 3}}, "data"), ConfigError);
  try {
    ReadJsonOptions<TrainingScenesOptions>(nlohmann::json{{"hours_per_scene", 1}}, "data");
    FAIL() << "read hours_per_scene 1";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "data: hours_per_scene: must be in [2, 12], got 1");
  }
}

TEST(TrainingScenes, AreDeterministic) {
  const TrainingScenesOptions options;
  for (int i = 0; i < options.scenes; ++i) {
    const TrainingScene a = MakeTrainingScene(options, i), b = MakeTrainingScene(options, i);
    EXPECT_EQ(a.index, i);
    EXPECT_EQ(a.config.seed, b.config.seed);
    EXPECT_EQ(a.furniture_signature, b.furniture_signature);
    EXPECT_EQ(ToJsonObject(a.config).dump(), ToJsonObject(b.config).dump());
  }
}

TEST(TrainingScenes, DifferFromEachOtherAndFromAnotherBaseSeed) {
  const TrainingScenesOptions options = Many();
  std::set<uint64_t> seeds, texture_seeds, paint_seeds;
  std::set<std::string> signatures;
  std::set<int> days;
  for (int i = 0; i < kManyScenes; ++i) {
    const TrainingScene s = MakeTrainingScene(options, i);
    seeds.insert(s.config.seed);
    texture_seeds.insert(s.config.scene.seed);
    paint_seeds.insert(s.config.scene.wall_paint_seed);
    signatures.insert(s.furniture_signature);
    days.insert(s.config.lighting.site.day_of_year);
  }
  EXPECT_EQ(seeds.size(), static_cast<size_t>(kManyScenes));
  EXPECT_EQ(texture_seeds.size(), static_cast<size_t>(kManyScenes));
  EXPECT_EQ(paint_seeds.size(), static_cast<size_t>(kManyScenes));
  EXPECT_EQ(signatures.size(), static_cast<size_t>(kManyScenes));
  EXPECT_GT(days.size(), 150u);  // spread over the year
  TrainingScenesOptions other = options;
  other.seed = options.seed + 1;
  EXPECT_NE(MakeTrainingScene(other, 0).config.seed, MakeTrainingScene(options, 0).config.seed);
}

// The held-out rule: no scene has the default dataset's seed, texture seed
// (the config's, or the one the generator derives from its seed) or
// furniture arrangement.
TEST(TrainingScenes, NeverUseTheDefaultDatasetsSeedsOrArrangement) {
  const GeneratorConfig defaults;
  const std::string default_signature = FurnitureSignature(defaults.scene.furniture);
  ASSERT_FALSE(defaults.scene.furniture.pieces.empty());
  const TrainingScenesOptions options = Many();
  for (int i = 0; i < kManyScenes; ++i) {
    const TrainingScene s = MakeTrainingScene(options, i);
    EXPECT_NE(s.config.seed, defaults.seed);
    EXPECT_NE(s.config.scene.seed, defaults.scene.seed);
    EXPECT_NE(s.config.scene.seed, DeriveSeed(defaults.seed, 1));
    EXPECT_EQ(s.config.scene.seed, DeriveSeed(s.config.seed, 1));  // what the generator would use
    EXPECT_NE(s.config.scene.wall_paint_seed, 0u);
    EXPECT_NE(s.furniture_signature, default_signature);
    EXPECT_EQ(s.furniture_signature, FurnitureSignature(s.config.scene.furniture));
  }
}

TEST(FurnitureSignature, ChangesWithEveryField) {
  FurnitureOptions a;
  a.pieces = {{"chair", "kitchen", Eigen::Vector2d(1, 2), 10.0, 0.0}};
  const std::string base = FurnitureSignature(a);
  FurnitureOptions b = a;
  b.pieces[0].model = "chair2";
  EXPECT_NE(FurnitureSignature(b), base);
  b = a;
  b.pieces[0].room = "bedroom";
  EXPECT_NE(FurnitureSignature(b), base);
  b = a;
  b.pieces[0].position_m.y() += 0.001;
  EXPECT_NE(FurnitureSignature(b), base);
  b = a;
  b.pieces[0].yaw_deg += 0.01;
  EXPECT_NE(FurnitureSignature(b), base);
  b = a;
  b.pieces[0].elevation_m = 0.5;
  EXPECT_NE(FurnitureSignature(b), base);
  b.pieces.push_back(a.pieces[0]);
  EXPECT_NE(FurnitureSignature(b), base);
}

TEST(TrainingScenes, ClockTimesSpanFullDayToLampLitNight) {
  TrainingScenesOptions options = Many();
  options.hours_per_scene = 5;
  for (int i = 0; i < kManyScenes; ++i) {
    const GeneratorConfig config = MakeTrainingScene(options, i).config;
    ASSERT_EQ(config.sessions.size(), 5u);
    const double sunset = ComputeSunsetTime(config.lighting.site);
    double last = -1.0;
    for (size_t k = 0; k < config.sessions.size(); ++k) {
      EXPECT_EQ(config.sessions[k].name, std::to_string(k + 1));
      EXPECT_EQ(config.sessions[k].role, "mapping");
      const double h = ParseClockTime(config.sessions[k].clock_time, "session");
      EXPECT_GT(h, last) << "scene " << i;
      last = h;
    }
    const double first = ParseClockTime(config.sessions.front().clock_time, "first");
    const double night = ParseClockTime(config.sessions.back().clock_time, "last");
    EXPECT_GE(first, 10.0 - 1e-9);
    EXPECT_LE(first, 15.0 + 1e-9);
    EXPECT_LT(first, sunset - 2.0);  // full day
    EXPECT_GE(night, sunset + 1.2);  // past civil twilight
    EXPECT_LE(night, 23.0 + 1e-9);
    EXPECT_EQ(config.max_frames, options.frames_per_hour);
  }
}

TEST(TrainingScenes, LampsVaryAcrossScenes) {
  const TrainingScenesOptions options = Many();
  int bedroom_on = 0, living_on = 0, neither = 0;
  std::set<std::string> floor_lamp_times;
  for (int i = 0; i < kManyScenes; ++i) {
    const LampOptions lamps = MakeTrainingScene(options, i).config.scene.lamps;
    bedroom_on += lamps.bedroom_ceiling_cd > 0.0;
    living_on += lamps.living_ceiling_cd > 0.0;
    neither += lamps.bedroom_ceiling_cd == 0.0 && lamps.living_ceiling_cd == 0.0;
    floor_lamp_times.insert(lamps.living_lamp_on_from);
    EXPECT_NO_THROW(lamps.Check());
  }
  EXPECT_GT(bedroom_on, kManyScenes / 4);
  EXPECT_LT(bedroom_on, 3 * kManyScenes / 4);
  EXPECT_GT(living_on, kManyScenes / 4);
  EXPECT_LT(living_on, 3 * kManyScenes / 4);
  EXPECT_GT(neither, kManyScenes / 10);  // nights lit by the floor lamp only
  EXPECT_GT(floor_lamp_times.size(), 50u);
}

TEST(TrainingScenes, SomeHavePhotoMaterialsAndEveryConfigPassesItsCheck) {
  const TrainingScenesOptions options = Many();
  int with_photos = 0;
  std::set<std::string> images;
  for (int i = 0; i < kManyScenes; ++i) {
    const GeneratorConfig config = MakeTrainingScene(options, i).config;
    EXPECT_NO_THROW(config.Check()) << "scene " << i;
    with_photos += !config.scene.photo_materials.empty();
    for (const PhotoMaterialSpec& spec : config.scene.photo_materials) images.insert(spec.image);
  }
  EXPECT_GT(with_photos, kManyScenes / 4);
  EXPECT_LT(with_photos, 9 * kManyScenes / 10);
  EXPECT_GT(images.size(), 20u);
}

// Every piece stays inside its room and no closer to the patrol route than
// its default place was (or 0.3 m); objects above the floor stand on a
// surface of the height they are at.
TEST(TrainingScenes, FurnitureStaysInItsRoomAndOffTheRoute) {
  const TrainingScenesOptions options = Many();
  const std::vector<RoomFloor> floors = ApartmentRoomFloors();
  const std::vector<RouteWaypoint> route = ApartmentPatrolRoute();
  std::set<std::string> models;
  size_t fewest = 1000, most = 0;
  for (int i = 0; i < kManyScenes; ++i) {
    const std::vector<FurniturePiece> pieces = MakeTrainingScene(options, i).config.scene.furniture.pieces;
    fewest = std::min(fewest, pieces.size());
    most = std::max(most, pieces.size());
    for (const FurniturePiece& p : pieces) {
      models.insert(p.model);
      const Eigen::Vector3d size = TrainingFurnitureSize(p.model);
      const Eigen::Vector2d half = FootprintHalfExtentsM(p, size);
      const RoomFloor* floor = nullptr;
      for (const RoomFloor& f : floors) floor = f.name == p.room ? &f : floor;
      ASSERT_NE(floor, nullptr) << p.room;
      EXPECT_TRUE(((p.position_m - half - floor->min_xy).array() >= -1e-6).all()) << p.model << " scene " << i;
      EXPECT_TRUE(((floor->max_xy - p.position_m - half).array() >= -1e-6).all()) << p.model << " scene " << i;
      EXPECT_GE(p.elevation_m, 0.0);
      EXPECT_LT(p.elevation_m + size.z(), 2.5) << p.model;
    }
  }
  EXPECT_GT(models.size(), 60u);                   // drawn from the catalog
  EXPECT_LT(fewest, DefaultFurniturePieces().size());  // small pieces left out
  EXPECT_LE(most, DefaultFurniturePieces().size());
  // The route clearance of the arrangements of 50 seeds, against the default places nearby.
  for (uint64_t seed = 1; seed <= 50; ++seed) {
    for (const FurniturePiece& p : DrawTrainingFurniture(seed)) {
      double asked = 0.3;
      for (const FurniturePiece& d : DefaultFurniturePieces()) {
        if ((d.position_m - p.position_m).norm() < 0.5 && d.room == p.room) {
          asked = std::min(asked, RouteClearanceM(d, TrainingFurnitureSize(d.model), route));
        }
      }
      EXPECT_GE(RouteClearanceM(p, TrainingFurnitureSize(p.model), route), asked - 0.006) << p.model;
    }
  }
}

// The largest share of a floor piece's footprint (a 32 x 32 grid) inside
// another floor piece's.
double LargestFloorOverlap(const std::vector<FurniturePiece>& pieces) {
  double largest = 0.0;
  for (const FurniturePiece& p : pieces) {
    for (const FurniturePiece& q : pieces) {
      if (&q == &p || p.elevation_m != 0.0 || q.elevation_m != 0.0) continue;
      const Eigen::Vector3d size = TrainingFurnitureSize(p.model), q_size = TrainingFurnitureSize(q.model);
      int inside = 0;
      for (int i = 0; i < 32; ++i) {
        for (int j = 0; j < 32; ++j) {
          const Eigen::Vector2d local(((i + 0.5) / 32 - 0.5) * size.x(), ((j + 0.5) / 32 - 0.5) * size.y());
          const Eigen::Vector2d point = p.position_m + Eigen::Rotation2Dd(p.yaw_deg * M_PI / 180.0) * local;
          const Eigen::Vector2d in_q = Eigen::Rotation2Dd(-q.yaw_deg * M_PI / 180.0) * (point - q.position_m);
          inside += std::abs(in_q.x()) <= 0.5 * q_size.x() && std::abs(in_q.y()) <= 0.5 * q_size.y();
        }
      }
      largest = std::max(largest, inside / 1024.0);
    }
  }
  return largest;
}

// Chairs stay tucked at their table, not in it: no floor piece covers much
// more of the others than the default arrangement's pieces do.
TEST(TrainingScenes, FloorPiecesOverlapNoMoreThanTheDefaultOnes) {
  const double default_overlap = LargestFloorOverlap(DefaultFurniturePieces());
  EXPECT_LT(default_overlap, 0.2);
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    EXPECT_LE(LargestFloorOverlap(DrawTrainingFurniture(seed)), default_overlap + 0.1) << "seed " << seed;
  }
}

TEST(RouteClearance, IsTheDistanceFromTheTurnedFootprintToThePolyline) {
  std::vector<RouteWaypoint> route(2);
  route[0].position_xy = {0.0, 0.0};
  route[1].position_xy = {4.0, 0.0};
  FurniturePiece piece{"chair", "kitchen", Eigen::Vector2d(2.0, 1.0), 0.0, 0.0};
  EXPECT_NEAR(RouteClearanceM(piece, {1.0, 0.5, 1.0}, route), 0.75, 1e-9);
  piece.yaw_deg = 90.0;  // the 1 m side now along y
  EXPECT_NEAR(RouteClearanceM(piece, {1.0, 0.5, 1.0}, route), 0.5, 1e-9);
  piece.position_m = {2.0, 0.2};  // across the route
  EXPECT_EQ(RouteClearanceM(piece, {1.0, 0.5, 1.0}, route), 0.0);
  piece.position_m = {0.0, 0.0};  // around a waypoint
  EXPECT_EQ(RouteClearanceM(piece, {0.2, 0.2, 1.0}, route), 0.0);
  piece.position_m = {5.0, 0.0};  // beyond the end
  piece.yaw_deg = 0.0;
  EXPECT_NEAR(RouteClearanceM(piece, {1.0, 0.5, 1.0}, route), 0.5, 1e-9);
}

// The model table's sizes are the installed catalog's, and every photo the
// scenes draw is in it.
TEST(TrainingScenes, ModelsAndPhotosAreTheInstalledCatalogs) {
  if (!std::filesystem::exists(DefaultFurnitureCatalogPath())) {
    GTEST_SKIP() << "sweethome3d-furniture not installed: run scripts/setup.sh";
  }
  const FurnitureCatalog catalog = FurnitureCatalog::Open(DefaultFurnitureCatalogPath());
  for (const TrainingFurnitureModel& m : TrainingFurnitureModels()) {
    const FurnitureEntry& entry = catalog.Find(m.model);
    EXPECT_TRUE(entry.size_cm.isApprox(100.0 * m.size_m, 1e-3)) << m.model << ": " << entry.size_cm.transpose();
  }
  const TrainingScenesOptions options = Many();
  for (int i = 0; i < kManyScenes; ++i) {
    for (const PhotoMaterialSpec& spec : MakeTrainingScene(options, i).config.scene.photo_materials) {
      EXPECT_TRUE(catalog.Contains(spec.image)) << spec.image;
    }
  }
}

// One scene with photo materials built with the installed catalog: every
// piece is there, inside its room, on or above the floor and below the ceiling.
TEST(TrainingScenes, OneBuildsWithItsPiecesInsideTheirRooms) {
  if (!std::filesystem::exists(DefaultFurnitureCatalogPath())) {
    GTEST_SKIP() << "sweethome3d-furniture not installed: run scripts/setup.sh";
  }
  const TrainingScenesOptions options;
  int index = 0;
  while (MakeTrainingScene(options, index).config.scene.photo_materials.empty()) ++index;
  const GeneratorConfig config = MakeTrainingScene(options, index).config;
  const Scene scene = BuildApartment(config.scene);
  EXPECT_EQ(scene.meshes.size(), config.scene.furniture.pieces.size());
  EXPECT_EQ(scene.material_credits.empty(), false);
  const std::vector<RoomFloor> floors = ApartmentRoomFloors();
  for (const SceneMesh& mesh : scene.meshes) {
    const RoomFloor& floor = floors[static_cast<size_t>(mesh.room)];
    const Eigen::AlignedBox3d& box = mesh.bounds_in_world;
    EXPECT_GE(box.min().x(), floor.min_xy.x() - 0.02) << mesh.model_id;
    EXPECT_GE(box.min().y(), floor.min_xy.y() - 0.02) << mesh.model_id;
    EXPECT_LE(box.max().x(), floor.max_xy.x() + 0.02) << mesh.model_id;
    EXPECT_LE(box.max().y(), floor.max_xy.y() + 0.02) << mesh.model_id;
    EXPECT_GE(box.min().z(), -0.02) << mesh.model_id;
    EXPECT_LE(box.max().z(), 2.45) << mesh.model_id;
  }
}

}  // namespace
}  // namespace duskmap
