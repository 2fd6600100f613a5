#include "slam/synthetic/assets/mtl_file.h"

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(ParseMtl, ReadsColoursOpacityAndTextureOptions) {
  const std::vector<MtlMaterial> materials = ParseMtl(
      "# Blender MTL\n"
      "newmtl wood\n"
      "Ns 96\nKa 0 0 0\nKd 0.6 0.4 0.2\nKs 0.5 0.5 0.5\nillum 2\n"
      "map_Kd -s 2 3 1 -o 0.5 0.25 my wood.jpg\t\t\n"
      "newmtl glass\n"
      "Kd 0.9\nTr 0.75\n"
      "newmtl both\n"
      "Tr 0.9\nd 0.5\n"
      "newmtl glass\n"
      "Kd 0 0 0\n",
      "m.mtl");
  ASSERT_EQ(materials.size(), 3u);
  EXPECT_EQ(materials[0].name, "wood");
  EXPECT_TRUE(materials[0].diffuse_rgb.isApprox(Eigen::Vector3f(0.6f, 0.4f, 0.2f)));
  EXPECT_FALSE(materials[0].dissolve.has_value());
  ASSERT_TRUE(materials[0].diffuse_map.has_value());
  EXPECT_EQ(materials[0].diffuse_map->file_name, "my wood.jpg");
  EXPECT_EQ(materials[0].diffuse_map->line, 8);
  EXPECT_TRUE(materials[0].diffuse_map->scale.isApprox(Eigen::Vector2f(2, 3)));
  EXPECT_TRUE(materials[0].diffuse_map->offset.isApprox(Eigen::Vector2f(0.5f, 0.25f)));
  EXPECT_TRUE(materials[1].diffuse_rgb.isApprox(Eigen::Vector3f::Constant(0.9f)));  // the first "glass" kept
  EXPECT_FLOAT_EQ(*materials[1].dissolve, 0.25f);
  EXPECT_FLOAT_EQ(*materials[2].dissolve, 0.5f);  // d wins over Tr
}

struct BadMtl {
  const char* text;
  const char* message;
};

TEST(ParseMtl, RefusesMalformedStatementsNamingTheFileAndLine) {
  for (const BadMtl& bad : {
           BadMtl{"newmtl a\nKd 0.5 x 0.5\n", "m.mtl:2: Kd: malformed number 'x'"},
           BadMtl{"newmtl a\nKd 0.5 0.5\n", "m.mtl:2: Kd needs 1 or 3 numbers, got 2"},
           BadMtl{"newmtl a\nKd -1 0 0\n", "m.mtl:2: Kd: -1 is outside [0, 1e+06]"},
           BadMtl{"newmtl a\nKd spectral file.rfl\n", "m.mtl:2: Kd spectral is not supported (only r g b)"},
           BadMtl{"newmtl a\nd 1.5\n", "m.mtl:2: d: 1.5 is outside [0, 1]"},
           BadMtl{"newmtl a\nd -halo 0.5\n", "m.mtl:2: d -halo is not supported"},
           BadMtl{"Kd 1 1 1\n", "m.mtl:1: Kd before the first newmtl"},
           BadMtl{"newmtl\n", "m.mtl:1: newmtl without a name"},
           BadMtl{"newmtl a\n\nmap_Kd\n", "m.mtl:3: map_Kd has no file name"},
           BadMtl{"newmtl a\nmap_Kd -blendu off wood.jpg\n",
                  "m.mtl:2: map_Kd option -blendu is not supported (only -s and -o)"},
           BadMtl{"newmtl a\nmap_Kd -s wood.jpg\n", "m.mtl:2: map_Kd -s needs a number"},
       }) {
    EXPECT_EQ(InputErrorOf([&] { ParseMtl(bad.text, "m.mtl"); }), bad.message) << bad.text;
  }
}

}  // namespace
}  // namespace duskmap
