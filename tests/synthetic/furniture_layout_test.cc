#include "slam/synthetic/scene/furniture_layout.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"
#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/scene/apartment.h"

namespace duskmap {
namespace {

// One piece: a 1 x 1 x 1 box model (OBJ units), shown at 40 x 60 x 80 cm.
const char kProperties[] =
    "id=Test#Catalog\nname=Test\nlicense=Public domain\n"
    "id#1=Test#crate\nname#1=Crate\nmodel#1=/crate/crate.obj\nwidth#1=40\ndepth#1=60\nheight#1=80\n"
    "creator#1=Maker\n";

// A unit cube, faces outward (OBJ: y up).
const char kCrateObj[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

class FurnitureLayoutTest : public ::testing::Test {
 protected:
  FurnitureLayoutTest() : scratch_("layout") {
    catalog_ = scratch_.File("test.sh3f");
    WriteZip(catalog_, {{"PluginFurnitureCatalog.properties", kProperties}, {"crate/crate.obj", kCrateObj}});
  }
  Scene RoomScene() const {
    Scene scene;
    scene.room_names = {"living room", "kitchen"};
    return scene;
  }
  FurnitureOptions Options(const std::string& room) const {
    FurnitureOptions options;
    options.catalog = catalog_;
    FurniturePiece piece;
    piece.model = "crate";
    piece.room = room;
    piece.position_m = Eigen::Vector2d(2.0, 3.0);
    piece.yaw_deg = 90.0;
    piece.elevation_m = 0.5;
    options.pieces = {piece, piece};
    options.pieces[1].position_m = Eigen::Vector2d(5.0, 1.0);
    options.pieces[1].yaw_deg = 0.0;
    options.pieces[1].elevation_m = 0.0;
    return options;
  }
  ScratchFolder scratch_;
  std::string catalog_;
};

TEST_F(FurnitureLayoutTest, PlacesEachPieceTurnedAndMovedInItsRoom) {
  Scene scene = RoomScene();
  AddFurniture(Options("kitchen"), &scene);
  ASSERT_EQ(scene.meshes.size(), 2u);
  const SceneMesh& turned = scene.meshes[0];
  EXPECT_EQ(turned.room, 1);
  EXPECT_EQ(turned.name, "Crate");
  EXPECT_EQ(turned.model_id, "Test#crate");
  EXPECT_EQ(turned.creator, "Maker");
  EXPECT_EQ(turned.license, "Public domain");
  EXPECT_EQ(turned.catalog, "test.sh3f");
  // 40 cm wide along x and 60 cm deep along y, turned by 90°: 60 cm along x,
  // 40 cm along y, centred on (2, 3), from 0.5 m to 1.3 m high.
  const Eigen::AlignedBox3d& a = turned.bounds_in_world;
  EXPECT_NEAR(a.min().x(), 1.7, 1e-5);
  EXPECT_NEAR(a.max().x(), 2.3, 1e-5);
  EXPECT_NEAR(a.min().y(), 2.8, 1e-5);
  EXPECT_NEAR(a.max().y(), 3.2, 1e-5);
  EXPECT_NEAR(a.min().z(), 0.5, 1e-5);
  EXPECT_NEAR(a.max().z(), 1.3, 1e-5);
  const Eigen::AlignedBox3d& b = scene.meshes[1].bounds_in_world;
  EXPECT_NEAR(b.sizes().x(), 0.4, 1e-5);
  EXPECT_NEAR(b.sizes().y(), 0.6, 1e-5);
  EXPECT_NEAR(b.center().x(), 5.0, 1e-5);
  // Long edges split (max_edge_m 0.12): the 0.8 m edges into 8 at least.
  EXPECT_GT(turned.triangles.size(), 12u * 8u);
  // Shadow rays see the pieces.
  EXPECT_TRUE(scene.mesh_occluders.Occluded({2.0, 3.0, 2.0}, {0, 0, -1}, 5.0));
  EXPECT_FALSE(scene.mesh_occluders.Occluded({3.0, 3.0, 2.0}, {0, 0, -1}, 5.0));
}

TEST_F(FurnitureLayoutTest, BadPiecesNameTheProblem) {
  Scene scene = RoomScene();
  try {
    AddFurniture(Options("attic"), &scene);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "scene.furniture.pieces[0].room: no room 'attic'");
  }
  FurnitureOptions options = Options("kitchen");
  options.pieces[1].model = "piano";
  const std::string absent = InputErrorOf([&] { AddFurniture(options, &scene); });
  EXPECT_NE(absent.find("test.sh3f"), std::string::npos) << absent;
  EXPECT_NE(absent.find("piano"), std::string::npos) << absent;
  options = Options("kitchen");
  options.catalog = scratch_.File("missing.sh3f");
  const std::string missing = InputErrorOf([&] { AddFurniture(options, &scene); });
  EXPECT_NE(missing.find("missing.sh3f"), std::string::npos) << missing;
  EXPECT_NE(missing.find("scripts/setup.sh"), std::string::npos) << missing;
  EXPECT_TRUE(scene.meshes.empty());  // nothing half-added
  options = Options("kitchen");
  options.pieces[0].elevation_m = -1.0;
  EXPECT_THROW(options.Check(), ConfigError);
}

TEST_F(FurnitureLayoutTest, NoPiecesNeedNoCatalog) {
  Scene scene = RoomScene();
  FurnitureOptions options;
  options.catalog = scratch_.File("absent.sh3f");
  AddFurniture(options, &scene);
  EXPECT_TRUE(scene.meshes.empty());
  EXPECT_TRUE(scene.mesh_occluders.empty());
}

TEST_F(FurnitureLayoutTest, TheConfigReadsPiecesStrictly) {
  const std::string path = scratch_.File("config.json");
  WriteBytes(path, R"({"scene": {"box_furniture": false, "furniture": {"catalog": "c.sh3f", "pieces": [
      {"model": "crate", "room": "kitchen", "position_m": [1.5, 2.5], "yaw_deg": -90, "elevation_m": 0.9}]}}})");
  const GeneratorConfig config = ReadGeneratorConfig(path);
  EXPECT_FALSE(config.scene.box_furniture);
  ASSERT_EQ(config.scene.furniture.pieces.size(), 1u);
  EXPECT_EQ(config.scene.furniture.catalog, "c.sh3f");
  EXPECT_EQ(config.scene.furniture.pieces[0].position_m, Eigen::Vector2d(1.5, 2.5));
  EXPECT_EQ(config.scene.furniture.pieces[0].yaw_deg, -90.0);
  WriteBytes(path, R"({"scene": {"furniture": {"pieces": [{"model": "crate", "position_m": [1, 2]}]}}})");
  try {
    ReadGeneratorConfig(path);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.furniture.pieces[0]: missing key 'room'"), std::string::npos)
        << e.what();
  }
  WriteBytes(path, R"({"scene": {"furniture": {"pieces": [{"model": "crate", "room": "kitchen",
      "position_m": [1, 2], "colour": "red"}]}}})");
  EXPECT_THROW(ReadGeneratorConfig(path), ConfigError);
}

// The furnished config shipped in configs/ builds with the installed package.
TEST(FurnishedApartment, TheShippedConfigBuildsWithTheInstalledCatalog) {
  if (!std::filesystem::exists(DefaultFurnitureCatalogPath())) {
    GTEST_SKIP() << "sweethome3d-furniture not installed: run scripts/setup.sh";
  }
  const GeneratorConfig config =
      ReadGeneratorConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment.json");
  EXPECT_FALSE(config.scene.box_furniture);
  const Scene scene = BuildApartment(config.scene);
  EXPECT_EQ(scene.meshes.size(), config.scene.furniture.pieces.size());
  const Scene boxes = BuildApartment(ApartmentOptions());
  EXPECT_LT(scene.quads.size(), boxes.quads.size());  // the box furniture left out
  for (const SceneMesh& mesh : scene.meshes) {
    EXPECT_EQ(mesh.license, "Public domain") << mesh.name;
    // Inside the apartment's footprint, on or above the floor.
    EXPECT_GE(mesh.bounds_in_world.min().z(), -1e-4) << mesh.name;
    EXPECT_GE(mesh.bounds_in_world.min().x(), -1e-3) << mesh.name;
    EXPECT_LE(mesh.bounds_in_world.max().x(), 10.0) << mesh.name;
    EXPECT_LE(mesh.bounds_in_world.max().y(), 9.0) << mesh.name;
  }
}

}  // namespace
}  // namespace duskmap
