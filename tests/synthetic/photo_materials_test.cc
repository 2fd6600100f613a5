#include "slam/synthetic/scene/photo_materials.h"

#include <cmath>

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/scene/apartment.h"

namespace duskmap {
namespace {

// A catalog with one piece whose folder holds a photo, and a file that is
// not an image.
const char kProperties[] =
    "id=Test#Catalog\nname=Test\nlicense=Public domain\n"
    "id#1=Test#crate\nname#1=Crate\nmodel#1=/crate/crate.obj\nwidth#1=40\ndepth#1=60\nheight#1=80\n"
    "creator#1=Maker\nlicense#1=CC-BY 4.0\n";
const char kCrateObj[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";

// A photo whose every pixel differs: blue grows along the columns, green
// along the rows (sRGB bytes), so a texel tells where in the photo it lies.
cv::Mat IndexPhoto(int width, int height) {
  cv::Mat photo(height, width, CV_8UC3);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) photo.at<cv::Vec3b>(r, c) = cv::Vec3b(40 + 3 * c, 40 + 3 * r, 128);
  }
  return photo;
}

class PhotoMaterialsTest : public ::testing::Test {
 protected:
  PhotoMaterialsTest() : scratch_("photo_materials") {
    catalog_ = scratch_.File("test.sh3f");
    WriteZip(catalog_, {{"PluginFurnitureCatalog.properties", kProperties},
                        {"crate/crate.obj", kCrateObj},
                        {"crate/grain.png", EncodeImage(IndexPhoto(64, 48), ".png")},
                        {"loose/plain.png", EncodeImage(cv::Mat(8, 8, CV_8UC3, cv::Scalar(90, 90, 90)), ".png")},
                        {"crate/notes.txt", "not an image"}});
  }
  static PhotoMaterialSpec Spec(const std::string& surface, const std::string& image) {
    PhotoMaterialSpec spec;
    spec.surface = surface;
    spec.image = image;
    spec.width_m = 0.64;   // 64 texels of 1 cm: one photo pixel per texel
    spec.texel_m = 0.01;
    return spec;
  }
  ScratchFolder scratch_;
  std::string catalog_;
};

TEST_F(PhotoMaterialsTest, LoadsEachPhotoAtItsTexelSizeAndCreditsItsPiece) {
  PhotoMaterialSpec floor = Spec("wood_floor", "crate/grain.png");
  floor.texel_m = 0.02;  // 32 x 24 texels
  const LoadedPhotoMaterials loaded =
      LoadPhotoMaterials({floor, Spec("tiles", "crate/grain.png"), Spec("counter", "loose/plain.png")}, catalog_);
  ASSERT_EQ(loaded.materials.size(), 3u);
  EXPECT_EQ(loaded.materials[0].kind, TextureKind::kWoodFloor);
  EXPECT_EQ(loaded.materials[0].texels.size(), cv::Size(32, 24));
  EXPECT_EQ(loaded.materials[0].texels.type(), CV_32FC3);
  EXPECT_DOUBLE_EQ(loaded.materials[0].texel_m, 0.02);
  EXPECT_EQ(loaded.materials[1].texels.size(), cv::Size(64, 48));
  EXPECT_EQ(loaded.materials[2].texels.size(), cv::Size(64, 64));
  // Linear values: sRGB 90 is 0.1022 linear.
  EXPECT_NEAR(loaded.materials[2].texels.at<cv::Vec3f>(5, 5)[0], 0.1022, 0.002);
  // One credit per image; the piece in the photo's folder gives its creator and licence.
  ASSERT_EQ(loaded.credits.size(), 2u);
  EXPECT_EQ(loaded.credits[0].name, "grain.png");
  EXPECT_EQ(loaded.credits[0].source, "test.sh3f#crate/grain.png");
  EXPECT_EQ(loaded.credits[0].creator, "Maker");
  EXPECT_EQ(loaded.credits[0].license, "CC-BY 4.0");
  EXPECT_EQ(loaded.credits[1].creator, "");
  EXPECT_EQ(loaded.credits[1].license, "Public domain");  // the catalog's
  EXPECT_EQ(FindPhotoMaterial(loaded.materials, TextureKind::kTiles), &loaded.materials[1]);
  EXPECT_EQ(FindPhotoMaterial(loaded.materials, TextureKind::kFabric), nullptr);
}

TEST_F(PhotoMaterialsTest, BadSpecsAndImagesNameTheProblem) {
  EXPECT_THROW(LoadPhotoMaterials({Spec("ceiling", "crate/grain.png")}, catalog_), ConfigError);
  try {
    LoadPhotoMaterials({Spec("marble", "crate/grain.png")}, catalog_);
    ADD_FAILURE() << "an unknown surface was accepted";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "photo material surface 'marble' is not one of wood_floor, tiles, counter, wood, fabric");
  }
  PhotoMaterialSpec tiny = Spec("wood", "crate/grain.png");
  tiny.width_m = 0.05;
  tiny.texel_m = 0.01;  // 5 texels
  EXPECT_THROW(LoadPhotoMaterials({tiny}, catalog_), ConfigError);
  try {
    LoadPhotoMaterials({Spec("wood", "crate/grain.png"), Spec("wood", "loose/plain.png")}, catalog_);
    ADD_FAILURE() << "a surface given twice was accepted";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "scene.photo_materials[1].surface: 'wood' is given twice");
  }
  const std::string missing = InputErrorOf([&] { LoadPhotoMaterials({Spec("wood", "crate/none.png")}, catalog_); });
  EXPECT_NE(missing.find(catalog_ + "!/crate/none.png"), std::string::npos) << missing;
  const std::string not_image =
      InputErrorOf([&] { LoadPhotoMaterials({Spec("wood", "crate/notes.txt")}, catalog_); });
  EXPECT_EQ(not_image.rfind(catalog_ + "!/crate/notes.txt: ", 0), 0u) << not_image;
  const std::string no_catalog =
      InputErrorOf([&] { LoadPhotoMaterials({Spec("wood", "crate/grain.png")}, scratch_.File("none.sh3f")); });
  EXPECT_NE(no_catalog.find("none.sh3f"), std::string::npos) << no_catalog;
  // No specs need no catalog.
  EXPECT_TRUE(LoadPhotoMaterials({}, scratch_.File("none.sh3f")).materials.empty());
}

// The texel of the photo a surface texel shows, from its blue and green
// (IndexPhoto), as (column, row); (-1, -1) for a joint or grout texel.
cv::Point PhotoTexelOf(const cv::Mat& photo_texels, const cv::Vec3f& value) {
  for (int r = 0; r < photo_texels.rows; ++r) {
    for (int c = 0; c < photo_texels.cols; ++c) {
      const cv::Vec3f p = photo_texels.at<cv::Vec3f>(r, c);
      if (std::abs(p[0] - value[0]) < 1e-5f && std::abs(p[1] - value[1]) < 1e-5f) return {c, r};
    }
  }
  return {-1, -1};
}

TEST_F(PhotoMaterialsTest, TilesAreCropsOfThePhotoBetweenGrout) {
  LoadedPhotoMaterials loaded = LoadPhotoMaterials({Spec("tiles", "crate/grain.png")}, catalog_);
  const PhotoMaterial& tiles = loaded.materials[0];
  TextureRequest request;
  request.kind = TextureKind::kTiles;
  request.seed = 11;
  // The base colour is the photo's own mean, so the albedo holds the photo's values.
  const cv::Scalar mean = cv::mean(tiles.texels);
  request.base_bgr = cv::Vec3f(mean[0], mean[1], mean[2]);
  ReliefCanvas relief(cv::Size(60, 40), 0.01);
  const cv::Mat albedo = PhotoAlbedo(tiles, request, cv::Size(60, 40), relief);
  ASSERT_EQ(albedo.size(), cv::Size(60, 40));
  const int tile = 15;  // 0.152 m of 1 cm texels
  for (int k = 0; k < 60; k += tile) EXPECT_EQ(albedo.at<cv::Vec3f>(7, k), cv::Vec3f(0.35f, 0.35f, 0.35f));
  EXPECT_LT(relief.height_m().at<float>(7, tile), -0.002f);  // grout 3 mm back
  EXPECT_FLOAT_EQ(relief.height_m().at<float>(7, 7), 0.0f);
  // Inside a tile, neighbouring texels are neighbouring photo texels (modulo its size).
  const cv::Point a = PhotoTexelOf(tiles.texels, albedo.at<cv::Vec3f>(20, 20));
  const cv::Point b = PhotoTexelOf(tiles.texels, albedo.at<cv::Vec3f>(21, 22));
  ASSERT_GE(a.x, 0);
  ASSERT_GE(b.x, 0);
  EXPECT_EQ((b.x - a.x + 64) % 64, 2);
  EXPECT_EQ((b.y - a.y + 48) % 48, 1);
  // Two tiles are cut at different offsets.
  const cv::Point other = PhotoTexelOf(tiles.texels, albedo.at<cv::Vec3f>(20, 20 + tile));
  EXPECT_NE(other, a);
  // The same seed gives the same texture; another seed other offsets.
  ReliefCanvas none;
  EXPECT_EQ(cv::norm(albedo, PhotoAlbedo(tiles, request, cv::Size(60, 40), none), cv::NORM_INF), 0.0);
  request.seed = 12;
  EXPECT_GT(cv::norm(albedo, PhotoAlbedo(tiles, request, cv::Size(60, 40), none), cv::NORM_INF), 0.0);
}

TEST_F(PhotoMaterialsTest, PlanksTakeTheSurfacesColourWithJointsBetweenThem) {
  LoadedPhotoMaterials loaded = LoadPhotoMaterials({Spec("wood_floor", "loose/plain.png")}, catalog_);
  TextureRequest request;
  request.kind = TextureKind::kWoodFloor;
  request.base_bgr = cv::Vec3f(0.2f, 0.3f, 0.4f);
  request.seed = 5;
  ReliefCanvas relief(cv::Size(100, 300), 0.01);
  const cv::Mat albedo = PhotoAlbedo(loaded.materials[0], request, cv::Size(100, 300), relief);
  const int plank = 14;  // 0.144 m of 1 cm texels
  int joints = 0;
  for (int r = 0; r < albedo.rows; ++r) {
    for (int c = 0; c < albedo.cols; ++c) {
      const cv::Vec3f v = albedo.at<cv::Vec3f>(r, c);
      if (c % plank == 0) {
        EXPECT_NEAR(v[2], 0.4f * 0.35f, 1e-6f);  // the joint between planks
        continue;
      }
      if (std::abs(v[2] - 0.14f) < 1e-6f) {
        ++joints;  // a joint along a plank
        continue;
      }
      // The uniform photo at the base colour, times the plank's tone in [0.85, 1.15].
      const float tone = v[2] / 0.4f;
      EXPECT_GE(tone, 0.85f);
      EXPECT_LE(tone, 1.15f);
      EXPECT_NEAR(v[0] / 0.2f, tone, 1e-4f);
    }
  }
  // Each of the 92 plank columns (1-13, 15-27, ..., 99) has a joint every 120 texels: 2 or 3 in 300 rows.
  EXPECT_GE(joints, 92 * 2);
  EXPECT_LE(joints, 92 * 3);
  EXPECT_LT(relief.height_m().at<float>(10, plank), -0.002f);
}

TEST_F(PhotoMaterialsTest, TheApartmentDrawsItsSurfacesFromThePhotosAndCreditsThem) {
  ApartmentOptions options;
  options.seed = 3;
  options.furniture.catalog = catalog_;
  const Scene procedural = BuildApartment(options);
  options.photo_materials = {Spec("counter", "crate/grain.png")};
  const Scene photographic = BuildApartment(options);
  ASSERT_EQ(photographic.material_credits.size(), 1u);
  EXPECT_EQ(photographic.material_credits[0].source, "test.sh3f#crate/grain.png");
  EXPECT_TRUE(procedural.material_credits.empty());
  ASSERT_EQ(procedural.quads.size(), photographic.quads.size());
  // Only the counter's quads (its top and four sides) change, at the photo's texel size.
  int changed = 0;
  for (size_t i = 0; i < procedural.quads.size(); ++i) {
    const cv::Mat& a = procedural.quads[i].albedo;
    const cv::Mat& b = photographic.quads[i].albedo;
    if (a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0.0) continue;
    ++changed;
    const Quad& q = photographic.quads[i];
    EXPECT_EQ(b.cols, static_cast<int>(std::lround(q.size_u_m / 0.01))) << i;
  }
  EXPECT_EQ(changed, 5);
}

TEST_F(PhotoMaterialsTest, TheConfigReadsThemStrictly) {
  const std::string path = scratch_.File("config.json");
  WriteBytes(path, R"({"scene": {"photo_materials": [
      {"surface": "counter", "image": "a/b.jpg", "width_m": 0.5, "texel_m": 0.005}]}})");
  const GeneratorConfig config = ReadGeneratorConfig(path);
  ASSERT_EQ(config.scene.photo_materials.size(), 1u);
  EXPECT_EQ(config.scene.photo_materials[0].surface, "counter");
  EXPECT_EQ(config.scene.photo_materials[0].image, "a/b.jpg");
  EXPECT_EQ(config.scene.photo_materials[0].width_m, 0.5);
  EXPECT_EQ(config.scene.photo_materials[0].texel_m, 0.005);
  WriteBytes(path, R"({"scene": {"photo_materials": [{"surface": "counter"}]}})");
  try {
    ReadGeneratorConfig(path);
    ADD_FAILURE() << "a material without an image was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.photo_materials[0]: missing key 'image'"), std::string::npos)
        << e.what();
  }
  WriteBytes(path, R"({"scene": {"photo_materials": [{"surface": "counter", "image": "a.jpg", "tint": 1}]}})");
  EXPECT_THROW(ReadGeneratorConfig(path), ConfigError);
  WriteBytes(path, R"({"scene": {"photo_materials": [{"surface": "counter", "image": "a.jpg", "width_m": -1}]}})");
  EXPECT_THROW(ReadGeneratorConfig(path), ConfigError);
}

}  // namespace
}  // namespace duskmap
