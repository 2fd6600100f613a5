#include "slam/synthetic/assets/furniture_catalog.h"

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"
#include "slam/synthetic/assets/obj_mesh.h"

namespace duskmap {
namespace {

const char kProperties[] =
    "# A test catalog\n"
    "id=Test#Catalog\n"
    "name=Test catalog\n"
    "description=Two pieces \\\n    for tests\n"
    "version=1.0\n"
    "license=Public domain\n"
    "provider=duskmap\n"
    "\n"
    "id#1=Test#chair\n"
    "name#1=Caf\\u00e9 chair\n"
    "category#1=Living room\n"
    "model#1=/models/chair/chair.obj\n"
    "multiPartModel#1=true\n"
    "width#1=45.5\n"
    "depth#1=50\n"
    "height#1=90\n"
    "creator#1=Someone\\: else\n"
    "\n"
    "id#3=Test#box\n"
    "name#3=Box\n"
    "category#3=Miscellaneous\n"
    "model#3=/models/box.obj\n"
    "width#3=10\n"
    "depth#3=20\n"
    "height#3=30\n"
    "modelRotation#3=1 0 0 0 0 1 0 -1 0\n"
    "license#3=CC-BY\n"
    "\n"
    "id#2=Test#box2\n"
    "name#2=Box\n"
    "model#2=models/box.obj\n"
    "width#2=1\n"
    "depth#2=1\n"
    "height#2=1\n";

const char kBoxObj[] =
    "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl wood\nf 1/1 2/2 3/3\n";

std::vector<std::pair<std::string, std::string>> CatalogFiles(const std::string& properties) {
  return {
      {"PluginFurnitureCatalog.properties", properties},
      {"models/chair/chair.obj", kBoxObj},
      {"models/chair/box.mtl", "newmtl wood\nKd 0.5 0.4 0.3\nmap_Kd wood.png\n"},
      {"models/chair/wood.png", EncodeImage(cv::Mat(4, 4, CV_8UC3, cv::Scalar(40, 80, 120)), ".png")},
      {"models/box.obj", kBoxObj},
      {"models/box.mtl", "newmtl wood\nKd 0.5 0.4 0.3\n"},
  };
}

class FurnitureCatalogTest : public ::testing::Test {
 protected:
  FurnitureCatalogTest() : scratch_("catalog") {}
  std::string Write(const std::string& name, const std::vector<std::pair<std::string, std::string>>& files) {
    const std::string path = scratch_.File(name);
    WriteZip(path, files);
    return path;
  }
  std::string OpenError(const std::string& properties) {
    const std::string path = Write("bad.sh3f", CatalogFiles(properties));
    return InputErrorOf([&] { FurnitureCatalog::Open(path); });
  }
  ScratchFolder scratch_;
};

TEST_F(FurnitureCatalogTest, ListsTheEntriesInTheOrderOfTheirNumbers) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(Write("test.sh3f", CatalogFiles(kProperties)));
  EXPECT_EQ(catalog.info().name, "Test catalog");
  EXPECT_EQ(catalog.info().description, "Two pieces for tests");
  EXPECT_EQ(catalog.info().license, "Public domain");
  ASSERT_EQ(catalog.entries().size(), 3u);
  const FurnitureEntry& chair = catalog.entries()[0];
  EXPECT_EQ(chair.index, 1);
  EXPECT_EQ(chair.id, "Test#chair");
  EXPECT_EQ(chair.Key(), "chair");
  EXPECT_EQ(chair.name, "Caf\xC3\xA9 chair");
  EXPECT_EQ(chair.category, "Living room");
  EXPECT_EQ(chair.creator, "Someone: else");
  EXPECT_EQ(chair.license, "Public domain");
  EXPECT_EQ(chair.model_path, "models/chair/chair.obj");
  EXPECT_TRUE(chair.multi_part_model);
  EXPECT_TRUE(chair.size_cm.isApprox(Eigen::Vector3d(45.5, 50, 90)));
  EXPECT_FALSE(chair.model_rotation.has_value());
  EXPECT_EQ(catalog.entries()[1].index, 2);
  EXPECT_EQ(catalog.entries()[1].model_path, "models/box.obj");  // without a leading '/' too
  const FurnitureEntry& box = catalog.entries()[2];
  EXPECT_EQ(box.license, "CC-BY");
  ASSERT_TRUE(box.model_rotation.has_value());
  Eigen::Matrix3d expected;
  expected << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  EXPECT_TRUE(box.model_rotation->isApprox(expected));
}

TEST_F(FurnitureCatalogTest, FindsByIdKeyOrUniqueName) {
  const std::string path = Write("test.sh3f", CatalogFiles(kProperties));
  const FurnitureCatalog catalog = FurnitureCatalog::Open(path);
  EXPECT_EQ(catalog.Find("Test#box").index, 3);
  EXPECT_EQ(catalog.Find("box2").index, 2);
  EXPECT_EQ(catalog.Find("Caf\xC3\xA9 chair").index, 1);
  EXPECT_EQ(InputErrorOf([&] { catalog.Find("Sofa"); }), path + ": no model 'Sofa' in the catalog");
  EXPECT_EQ(InputErrorOf([&] { catalog.Find("Box"); }),
            path + ": model name 'Box' is ambiguous (2 pieces: box2, box); give an id");
}

TEST_F(FurnitureCatalogTest, ReadsFilesAndRefusesPathsOutsideTheArchive) {
  const std::string path = Write("test.sh3f", CatalogFiles(kProperties));
  const FurnitureCatalog catalog = FurnitureCatalog::Open(path);
  EXPECT_TRUE(catalog.Contains("models/box.mtl"));
  EXPECT_FALSE(catalog.Contains("models/none.mtl"));
  EXPECT_EQ(catalog.ReadFile("models/box.mtl"), "newmtl wood\nKd 0.5 0.4 0.3\n");
  EXPECT_EQ(InputErrorOf([&] { catalog.ReadFile("../test.sh3f"); }),
            path + "!/../test.sh3f: path leaves the archive (absolute or '..')");
  EXPECT_EQ(InputErrorOf([&] { catalog.ReadFile("/etc/passwd"); }),
            path + "!//etc/passwd: path leaves the archive (absolute or '..')");
  EXPECT_EQ(InputErrorOf([&] { catalog.ReadFile("models/none.mtl"); }),
            path + "!/models/none.mtl: no such file in the archive");
}

TEST_F(FurnitureCatalogTest, FilesFeedTheObjLoader) {
  const FurnitureCatalog catalog = FurnitureCatalog::Open(Write("test.sh3f", CatalogFiles(kProperties)));
  const ObjLoadResult chair = LoadObjMesh(catalog.Find("chair").model_path, catalog.Files());
  ASSERT_EQ(chair.mesh.materials.size(), 1u);
  EXPECT_EQ(chair.mesh.materials[0].diffuse_texture_path, "models/chair/wood.png");
  EXPECT_EQ(chair.mesh.materials[0].diffuse_texture.size(), cv::Size(4, 4));
  const std::string message = InputErrorOf([&] { LoadObjMesh("models/missing.obj", catalog.Files()); });
  EXPECT_EQ(message, catalog.path() + "!/models/missing.obj: no such file");
}

TEST_F(FurnitureCatalogTest, AMissingCatalogNamesThePackageAndTheSetupScript) {
  const std::string path = scratch_.File("absent.sh3f");
  EXPECT_EQ(InputErrorOf([&] { FurnitureCatalog::Open(path); }),
            path + ": furniture catalog not found (install the Debian package sweethome3d-furniture: run "
                   "scripts/setup.sh)");
  EXPECT_EQ(DefaultFurnitureCatalogPath(), "/usr/share/sweethome3d/furniture/BlendSwap-CC-0.sh3f");
}

TEST_F(FurnitureCatalogTest, RefusesFilesThatAreNotCatalogs) {
  const std::string text = scratch_.File("text.sh3f");
  WriteBytes(text, "id=not a zip\n");
  EXPECT_EQ(InputErrorOf([&] { FurnitureCatalog::Open(text); }), text + ": not a ZIP archive");

  const std::string whole = ReadBytes(Write("whole.sh3f", CatalogFiles(kProperties)));
  const std::string cut = scratch_.File("cut.sh3f");
  WriteBytes(cut, whole.substr(0, whole.size() / 2));
  const std::string message = InputErrorOf([&] { FurnitureCatalog::Open(cut); });
  EXPECT_EQ(message.rfind(cut + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("ZIP archive"), std::string::npos) << message;

  const std::string plain = Write("plain.sh3f", {{"readme.txt", "hello"}});
  EXPECT_EQ(InputErrorOf([&] { FurnitureCatalog::Open(plain); }),
            plain + ": no PluginFurnitureCatalog.properties in the archive (not a SweetHome3D furniture catalog)");
}

TEST_F(FurnitureCatalogTest, RefusesEntriesWithoutAUsableModel) {
  const std::string source = scratch_.File("bad.sh3f") + "!/PluginFurnitureCatalog.properties: ";
  EXPECT_EQ(OpenError("name#1=Chair\nwidth#1=1\ndepth#1=1\nheight#1=1\n"), source + "entry #1 'Chair' has no model#1");
  EXPECT_EQ(OpenError("name#1=Evil\nmodel#1=/../evil/evil.obj\nwidth#1=1\ndepth#1=1\nheight#1=1\n"),
            source + "entry #1 'Evil': model#1 '/../evil/evil.obj' leaves the archive (absolute or '..')");
  EXPECT_EQ(OpenError("name#1=Evil\nmodel#1=../evil.obj\nwidth#1=1\ndepth#1=1\nheight#1=1\n"),
            source + "entry #1 'Evil': model#1 '../evil.obj' leaves the archive (absolute or '..')");
  EXPECT_EQ(OpenError("name#1=Evil\nmodel#1=//etc/evil.obj\nwidth#1=1\ndepth#1=1\nheight#1=1\n"),
            source + "entry #1 'Evil': model#1 '//etc/evil.obj' leaves the archive (absolute or '..')");
  EXPECT_EQ(OpenError("name#1=Gone\nmodel#1=/models/gone.obj\nwidth#1=1\ndepth#1=1\nheight#1=1\n"),
            source + "entry #1 'Gone': model#1 '/models/gone.obj' is not in the archive");
  EXPECT_EQ(OpenError("model#4=/models/box.obj\n"), source + "entry #4 has no name#4");
}

TEST_F(FurnitureCatalogTest, RefusesBadSizesAndRotations) {
  const std::string source = scratch_.File("bad.sh3f") + "!/PluginFurnitureCatalog.properties: ";
  const std::string head = "name#1=Box\nmodel#1=/models/box.obj\n";
  EXPECT_EQ(OpenError(head + "width#1=1\ndepth#1=1\n"), source + "entry #1 'Box' has no height#1");
  EXPECT_EQ(OpenError(head + "width#1=wide\ndepth#1=1\nheight#1=1\n"),
            source + "entry #1 'Box': width#1 must be a positive number (centimetres), got 'wide'");
  EXPECT_EQ(OpenError(head + "width#1=1\ndepth#1=-3\nheight#1=1\n"),
            source + "entry #1 'Box': depth#1 must be a positive number (centimetres), got '-3'");
  const std::string sized = head + "width#1=1\ndepth#1=1\nheight#1=1\n";
  EXPECT_EQ(OpenError(sized + "modelRotation#1=1 0 0 0 1 0 0 0\n"),
            source + "entry #1 'Box': modelRotation#1 must have 9 numbers, got 8");
  EXPECT_EQ(OpenError(sized + "modelRotation#1=1 0 0 0 1 0 0 0 x\n"),
            source + "entry #1 'Box': modelRotation#1 has a malformed number in '1 0 0 0 1 0 0 0 x'");
  EXPECT_EQ(OpenError(sized + "modelRotation#1=2 0 0 0 1 0 0 0 1\n"),
            source + "entry #1 'Box': modelRotation#1 is not a rotation: '2 0 0 0 1 0 0 0 1'");
  EXPECT_EQ(OpenError(sized + "modelRotation#1=-1 0 0 0 1 0 0 0 1\n"),
            source + "entry #1 'Box': modelRotation#1 is not a rotation: '-1 0 0 0 1 0 0 0 1'");
  EXPECT_EQ(OpenError("id=Empty\nname=No pieces\n"), source + "lists no furniture (no name#N/model#N keys)");
}

TEST(FurnitureCatalogOptions, CheckNamesTheField) {
  FurnitureCatalogOptions options;
  options.max_file_bytes = 0;
  try {
    options.Check();
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "furniture_catalog.max_file_bytes must be > 0, got 0");
  }
}

}  // namespace
}  // namespace duskmap
