// Tests on the installed BlendSwap-CC-0 catalog of Debian's
// sweethome3d-furniture package; they skip when it is not installed.
#include <filesystem>

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"
#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/assets/furniture_placement.h"

namespace duskmap {
namespace {

class BlendSwapCatalog : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(DefaultFurnitureCatalogPath())) {
      GTEST_SKIP() << "sweethome3d-furniture not installed: run scripts/setup.sh";
    }
  }
};

TEST_F(BlendSwapCatalog, ListsIts175PublicDomainPieces) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(DefaultFurnitureCatalogPath());
  EXPECT_EQ(catalog.info().name, "Blend Swap CC-0");
  EXPECT_EQ(catalog.info().license, "Public domain");
  ASSERT_EQ(catalog.entries().size(), 175u);
  for (const FurnitureEntry& entry : catalog.entries()) {
    EXPECT_EQ(entry.license, "Public domain") << entry.id;
    EXPECT_TRUE((entry.size_cm.array() > 0).all()) << entry.id;
    EXPECT_FALSE(entry.category.empty()) << entry.id;
  }
  const FurnitureEntry& bed = catalog.Find("bed1");
  EXPECT_EQ(bed.name, "Bed");
  EXPECT_EQ(bed.category, "Bedroom");
  EXPECT_EQ(bed.model_path, "blendswap-cc-0/bed1/bed1.obj");
  EXPECT_TRUE(bed.size_cm.isApprox(Eigen::Vector3d(140.7, 208, 95.5)));
  EXPECT_NE(InputErrorOf([&] { catalog.Find("Bed"); }).find("model name 'Bed' is ambiguous (4 pieces: bed1, bed2, "),
            std::string::npos);
  EXPECT_TRUE(catalog.Find("Apple iPhone").model_rotation.has_value());
}

// Loads a piece and checks its placed box against the catalog size (1 cm).
LoadedFurniture LoadAndCheckSize(const FurnitureCatalog& catalog, const std::string& name_or_id) {
  ObjLoadOptions options;
  options.skip_unavailable_textures = true;  // bed1 names a "C:/Documents and Settings/..." texture
  LoadedFurniture loaded = LoadFurniture(catalog, catalog.Find(name_or_id), options);
  const Eigen::AlignedBox3d box = loaded.mesh_in_furniture.Bounds();
  const Eigen::Vector3d size_m = loaded.entry.size_cm / 100.0;
  EXPECT_LT((box.sizes() - size_m).cwiseAbs().maxCoeff(), 0.01)
      << name_or_id << ": " << box.sizes().transpose() << " m vs catalog " << size_m.transpose();
  EXPECT_NEAR(box.min().z(), 0.0, 1e-4) << name_or_id;
  EXPECT_NEAR(box.center().x(), 0.0, 1e-4) << name_or_id;
  EXPECT_NEAR(box.center().y(), 0.0, 1e-4) << name_or_id;
  EXPECT_GT(loaded.mesh_in_furniture.triangles.size(), 100u) << name_or_id;
  return loaded;
}

int TexturedMaterials(const TriangleMesh& mesh) {
  int textured = 0;
  for (const Material& material : mesh.materials) {
    if (material.diffuse_texture.empty()) continue;
    ++textured;
    EXPECT_EQ(material.diffuse_texture.type(), CV_32FC3) << material.name;
    double min = 0, max = 0;
    cv::minMaxLoc(material.diffuse_texture.reshape(1), &min, &max);
    EXPECT_GE(min, 0.0) << material.name;
    EXPECT_LE(max, 1.0) << material.name;
    EXPECT_GT(max, min) << material.name;  // an image, not a flat colour
  }
  return textured;
}

TEST_F(BlendSwapCatalog, PlacesPiecesAtTheirCatalogSizes) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(DefaultFurnitureCatalogPath());
  for (const char* name : {"bed1", "Sofa", "Table", "Lamp", "Bookcase", "TV", "Desk lamp", "Apple iPhone"}) {
    LoadAndCheckSize(catalog, name);
  }
  const LoadedFurniture bed = LoadAndCheckSize(catalog, "bedWithTexture");
  EXPECT_EQ(TexturedMaterials(bed.mesh_in_furniture), 2);
  EXPECT_TRUE(bed.load.skipped_textures.empty());
  EXPECT_GT(TexturedMaterials(LoadAndCheckSize(catalog, "Table").mesh_in_furniture), 0);
  EXPECT_GT(TexturedMaterials(LoadAndCheckSize(catalog, "Bookcase").mesh_in_furniture), 0);
}

TEST_F(BlendSwapCatalog, ABedsTextureOutsideTheArchiveFailsUnlessSkipped) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(DefaultFurnitureCatalogPath());
  const FurnitureEntry& bed = catalog.Find("bed1");
  EXPECT_EQ(InputErrorOf([&] { LoadFurniture(catalog, bed); }),
            DefaultFurnitureCatalogPath() +
                "!/blendswap-cc-0/bed1/bed1.mtl:48: map_Kd 'C:/Documents and Settings/Jeremy.KIDSXP/Desktop/"
                "WoodFine0031_10_S.jpg' is outside the archive (absolute or '..')");
  ObjLoadOptions options;
  options.skip_unavailable_textures = true;
  const LoadedFurniture loaded = LoadFurniture(catalog, bed, options);
  ASSERT_EQ(loaded.load.skipped_textures.size(), 1u);
  EXPECT_EQ(loaded.load.skipped_textures[0].reason, "outside the archive (absolute or '..')");
}

TEST_F(BlendSwapCatalog, EveryPieceLoadsAtItsCatalogSize) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(DefaultFurnitureCatalogPath());
  ObjLoadOptions options;
  options.skip_unavailable_textures = true;
  int64_t triangles = 0;
  int textured = 0;
  for (const FurnitureEntry& entry : catalog.entries()) {
    const LoadedFurniture loaded = LoadFurniture(catalog, entry, options);
    const Eigen::Vector3d size_m = entry.size_cm / 100.0;
    EXPECT_LT((loaded.mesh_in_furniture.Bounds().sizes() - size_m).cwiseAbs().maxCoeff(), 0.01) << entry.id;
    triangles += static_cast<int64_t>(loaded.mesh_in_furniture.triangles.size());
    textured += loaded.mesh_in_furniture.TextureBytes() > 0;
  }
  EXPECT_GT(triangles, 2000000);
  EXPECT_GT(textured, 50);
}

// The catalog's width, height and depth are the models' own proportions
// along SweetHome3D's x, y and z (after modelRotation): scaling to them is
// nearly uniform, which checks the axes furniture_placement.h assumes.
TEST_F(BlendSwapCatalog, CatalogSizesAreTheModelsProportionsAlongXYZ) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(DefaultFurnitureCatalogPath());
  ObjLoadOptions options;
  options.skip_unavailable_textures = true;
  int uniform = 0;
  for (const FurnitureEntry& entry : catalog.entries()) {
    const ObjLoadResult loaded = LoadObjMesh(entry.model_path, catalog.Files(), options);
    const Eigen::Matrix3d rotation = entry.model_rotation.value_or(Eigen::Matrix3d::Identity());
    Eigen::AlignedBox3d box;
    for (const MeshTriangle& triangle : loaded.mesh.triangles) {
      for (const int index : triangle.position) box.extend(rotation * loaded.mesh.positions[index].cast<double>());
    }
    const Eigen::Vector3d size_xyz(entry.size_cm.x(), entry.size_cm.z(), entry.size_cm.y());
    const Eigen::Vector3d scale = size_xyz.cwiseQuotient(box.sizes());
    uniform += scale.maxCoeff() / scale.minCoeff() < 1.01;
  }
  EXPECT_GE(uniform, 150);  // 159 of 175 in BlendSwap-CC-0 1.8
}

}  // namespace
}  // namespace duskmap
