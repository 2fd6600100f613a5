#include "slam/synthetic/assets/obj_mesh.h"

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"

namespace duskmap {
namespace {

using Corners = std::array<int, 3>;

// A 4x2 sRGB image: left half red, right half blue (B G R order).
cv::Mat PictureImage() {
  cv::Mat image(2, 4, CV_8UC3, cv::Scalar(0, 0, 255));
  image(cv::Rect(2, 0, 2, 2)).setTo(cv::Scalar(255, 0, 0));
  return image;
}

FileMap TexturedQuadFiles() {
  return {
      {"models/quad/quad.obj",
       "# a textured unit quad\n"
       "mtllib quad.mtl\n"
       "o quad\n"
       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
       "vn 0 0 2\n"
       "usemtl picture\n"
       "s off\n"
       "f 1/1/1 2/2/1 3/3/1 4/4/1\n"},
      {"models/quad/quad.mtl",
       "newmtl picture\n"
       "Kd 1 0.5 0.25\n"
       "d 0.75\n"
       "map_Kd -s 2 2 -o 0.5 0 tex/picture.png\n"},
      {"models/quad/tex/picture.png", EncodeImage(PictureImage(), ".png")},
  };
}

TEST(LoadObjMesh, ReadsATexturedQuad) {
  const FileMap files = TexturedQuadFiles();
  const ObjLoadResult result = LoadObjMesh("models/quad/quad.obj", MemoryFiles(files));
  const TriangleMesh& mesh = result.mesh;
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.texcoords.size(), 4u);
  ASSERT_EQ(mesh.normals.size(), 1u);
  EXPECT_TRUE(mesh.normals[0].isApprox(Eigen::Vector3f(0, 0, 1)));  // normalised
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0].position, (Corners{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1].position, (Corners{0, 2, 3}));
  EXPECT_EQ(mesh.triangles[1].texcoord, (Corners{0, 2, 3}));
  EXPECT_EQ(mesh.triangles[1].normal, (Corners{0, 0, 0}));
  EXPECT_EQ(mesh.triangles[0].part, 0);
  EXPECT_EQ(mesh.part_names, std::vector<std::string>{"quad"});
  EXPECT_EQ(mesh.triangles[0].smoothing_group, 0);
  EXPECT_TRUE(mesh.texcoords[2].isApprox(Eigen::Vector2f(1, 1)));

  ASSERT_EQ(mesh.materials.size(), 1u);
  const Material& material = mesh.materials[0];
  EXPECT_EQ(material.name, "picture");
  EXPECT_EQ(material.diffuse_bgr, cv::Vec3f(0.25f, 0.5f, 1.0f));  // Kd is r g b
  EXPECT_FLOAT_EQ(*material.dissolve, 0.75f);
  EXPECT_TRUE(material.texture_scale.isApprox(Eigen::Vector2f(2, 2)));
  EXPECT_TRUE(material.texture_offset.isApprox(Eigen::Vector2f(0.5f, 0)));
  EXPECT_EQ(material.diffuse_texture_path, "models/quad/tex/picture.png");
  ASSERT_EQ(material.diffuse_texture.type(), CV_32FC3);
  ASSERT_EQ(material.diffuse_texture.size(), cv::Size(4, 2));
  EXPECT_EQ(material.diffuse_texture.at<cv::Vec3f>(0, 0), cv::Vec3f(0, 0, 1));  // red, linear BGR
  EXPECT_EQ(material.diffuse_texture.at<cv::Vec3f>(1, 3), cv::Vec3f(1, 0, 0));  // blue
  EXPECT_EQ(result.texture_file_bytes, static_cast<int64_t>(files.at("models/quad/tex/picture.png").size()));
  EXPECT_EQ(mesh.TextureBytes(), 4 * 2 * 3 * 4);
  EXPECT_EQ(result.num_faces, 1);
  EXPECT_TRUE(result.skipped_textures.empty());
  EXPECT_TRUE(result.undefined_materials.empty());
}

std::string CubeVertices() {
  return "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
         "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";
}

TEST(LoadObjMesh, NegativeIndicesCountBackFromTheLastVertex) {
  const FileMap files = {
      {"positive.obj", CubeVertices() +
                           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"},
      {"negative.obj", CubeVertices() +
                           "f -8 -5 -6 -7\nf -4 -3 -2 -1\nf -8 -7 -3 -4\nf -7 -6 -2 -3\nf -6 -5 -1 -2\n"
                           "f -5 -8 -4 -1\n"},
      // Relative to where the face is: each face after its own vertices.
      {"interleaved.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf -3 -2 -1\n"},
  };
  const ObjLoadResult positive = LoadObjMesh("positive.obj", MemoryFiles(files));
  const ObjLoadResult negative = LoadObjMesh("negative.obj", MemoryFiles(files));
  ASSERT_EQ(positive.mesh.triangles.size(), 12u);
  ASSERT_EQ(negative.mesh.triangles.size(), 12u);
  for (size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(negative.mesh.triangles[i].position, positive.mesh.triangles[i].position) << i;
  }
  const Eigen::AlignedBox3d box = negative.mesh.Bounds();
  EXPECT_TRUE(box.min().isApprox(Eigen::Vector3d(-1, -1, -1)));
  EXPECT_TRUE(box.max().isApprox(Eigen::Vector3d(1, 1, 1)));

  const ObjLoadResult interleaved = LoadObjMesh("interleaved.obj", MemoryFiles(files));
  ASSERT_EQ(interleaved.mesh.triangles.size(), 2u);
  EXPECT_EQ(interleaved.mesh.triangles[0].position, (Corners{0, 1, 2}));
  EXPECT_EQ(interleaved.mesh.triangles[1].position, (Corners{3, 4, 5}));
}

TEST(LoadObjMesh, FanTriangulatesPolygonsAndSkipsDegenerateFaces) {
  const FileMap files = {{"poly.obj",
                          "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nv -1 0.5 0\n"
                          "f 1 2 3 4 5\n"
                          "f 1// 2// 3// 4// 5// 6//\n"
                          "f 1 2\n"
                          "l 1 2 3\n"
                          "f 1 2 \\\n 3\n"  // continued line
                          "vp 0.5\n"}};
  const ObjLoadResult result = LoadObjMesh("poly.obj", MemoryFiles(files));
  const std::vector<MeshTriangle>& t = result.mesh.triangles;
  ASSERT_EQ(t.size(), 3u + 4u + 1u);
  EXPECT_EQ(t[0].position, (Corners{0, 1, 2}));
  EXPECT_EQ(t[1].position, (Corners{0, 2, 3}));
  EXPECT_EQ(t[2].position, (Corners{0, 3, 4}));
  EXPECT_EQ(t[6].position, (Corners{0, 4, 5}));
  EXPECT_EQ(t[6].texcoord, (Corners{-1, -1, -1}));
  EXPECT_EQ(t[7].position, (Corners{0, 1, 2}));
  EXPECT_EQ(result.num_faces, 4);
  EXPECT_EQ(result.num_degenerate_faces, 1);
  EXPECT_EQ(result.num_ignored_statements, 2);  // l and vp
  ASSERT_EQ(result.mesh.materials.size(), 1u);    // the default one
  EXPECT_EQ(result.mesh.materials[0].name, "");
}

TEST(LoadObjMesh, KeepsTheMaterialsTheFacesUseInOrderOfFirstUse) {
  const std::string texture = EncodeImage(cv::Mat(2, 2, CV_8UC3, cv::Scalar(10, 20, 30)), ".jpg");
  const FileMap files = {
      {"m/multi.obj",
       "mtllib a.mtl lib/b.mtl\n"
       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
       "f 1 2 3\n"
       "g top part\n"
       "usemtl red\ns 1\nf 1 2 3\n"
       "usemtl blue\nf 1 2 3 4\n"
       "g\n"
       "usemtl red\nf 1 3 4\n"
       "usemtl ghost\nf 2 3 4\n"
       "usemtl wood2\nf 1 2 4\n"},
      {"m/a.mtl",
       "newmtl red\nKd 1 0 0\nnewmtl unused\nKd 0 1 0\nmap_Kd missing.png\n"
       "newmtl wood2\nmap_Kd lib/wood.jpg\n"},
      {"m/lib/b.mtl", "newmtl blue\nKd 0 0 1\nmap_Kd wood.jpg\nnewmtl red\nKd 0 1 1\n"},
      {"m/lib/wood.jpg", texture},
  };
  const ObjLoadResult result = LoadObjMesh("m/multi.obj", MemoryFiles(files));
  const TriangleMesh& mesh = result.mesh;
  std::vector<std::string> names;
  for (const Material& m : mesh.materials) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"", "red", "blue", "ghost", "wood2"}));
  std::vector<int> materials, parts, groups;
  for (const MeshTriangle& t : mesh.triangles) {
    materials.push_back(t.material);
    parts.push_back(t.part);
    groups.push_back(t.smoothing_group);
  }
  EXPECT_EQ(materials, (std::vector<int>{0, 1, 2, 2, 1, 3, 4}));
  EXPECT_EQ(parts, (std::vector<int>{-1, 0, 0, 0, -1, -1, -1}));
  EXPECT_EQ(groups, (std::vector<int>{0, 1, 1, 1, 1, 1, 1}));
  EXPECT_EQ(mesh.part_names, std::vector<std::string>{"top part"});
  EXPECT_EQ(mesh.materials[1].diffuse_bgr, cv::Vec3f(0, 0, 1));  // a.mtl's red (the first definition)
  EXPECT_EQ(mesh.materials[2].diffuse_bgr, cv::Vec3f(1, 0, 0));
  EXPECT_EQ(mesh.materials[3].diffuse_bgr, cv::Vec3f(0.8f, 0.8f, 0.8f));
  EXPECT_EQ(result.undefined_materials, std::vector<std::string>{"ghost"});
  // blue and wood2 name the same file from two folders: decoded once, shared.
  EXPECT_EQ(mesh.materials[2].diffuse_texture_path, "m/lib/wood.jpg");
  EXPECT_EQ(mesh.materials[4].diffuse_texture_path, "m/lib/wood.jpg");
  EXPECT_EQ(mesh.materials[2].diffuse_texture.data, mesh.materials[4].diffuse_texture.data);
  EXPECT_EQ(result.texture_file_bytes, static_cast<int64_t>(texture.size()));
  EXPECT_EQ(mesh.TextureBytes(), 2 * 2 * 3 * 4);
  // "unused" names a missing texture, but no face uses it.
  EXPECT_TRUE(result.skipped_textures.empty());
}

// The quad's files with one file replaced (or removed, for "").
FileMap QuadWith(const std::string& path, const std::string& text) {
  FileMap files = TexturedQuadFiles();
  if (text.empty()) {
    files.erase(path);
  } else {
    files[path] = text;
  }
  return files;
}

std::string LoadError(const FileMap& files, const ObjLoadOptions& options = {}) {
  return InputErrorOf([&] { LoadObjMesh("models/quad/quad.obj", MemoryFiles(files), options); });
}

const char kObj[] = "models/quad/quad.obj";
const char kMtl[] = "models/quad/quad.mtl";

std::string Obj(const std::string& faces) { return "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\n" + faces; }

TEST(LoadObjMesh, RefusesBadIndicesNamingTheFileAndLine) {
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("f 0 1 2\n"))),
            "memory!/models/quad/quad.obj:6: face corner '0': position index 0 (OBJ indices start at 1)");
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("\nf 1 2 4\n"))),
            "memory!/models/quad/quad.obj:7: face corner '4': position index 4 is out of range (3 defined so far)");
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("f -1 -2 -4\n"))),
            "memory!/models/quad/quad.obj:6: face corner '-4': position index -4 is out of range (3 defined so "
            "far)");
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("f 1/1 2/2 3/1\n"))),
            "memory!/models/quad/quad.obj:6: face corner '2/2': texture coordinate index 2 is out of range (1 "
            "defined so far)");
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("f 1//1 2 3\n"))),
            "memory!/models/quad/quad.obj:6: face corner '1//1': normal index 1 is out of range (0 defined so far)");
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("f 1/x 2 3\n"))),
            "memory!/models/quad/quad.obj:6: malformed face corner '1/x'");
  EXPECT_EQ(LoadError(QuadWith(kObj, Obj("f 1/1/1/1 2 3\n"))),
            "memory!/models/quad/quad.obj:6: malformed face corner '1/1/1/1'");
}

TEST(LoadObjMesh, RefusesMalformedNumbersNamingTheFileAndLine) {
  EXPECT_EQ(LoadError(QuadWith(kObj, "v 0 0 0\nv 1 0 zero\n")),
            "memory!/models/quad/quad.obj:2: v: malformed number 'zero'");
  EXPECT_EQ(LoadError(QuadWith(kObj, "v 0 0 0\nv 1 0\n")),
            "memory!/models/quad/quad.obj:2: v needs 3 to 7 numbers, got 2");
  EXPECT_EQ(LoadError(QuadWith(kObj, "vn 0 0 nan\n")),
            "memory!/models/quad/quad.obj:1: vn: malformed number 'nan'");
  EXPECT_EQ(LoadError(QuadWith(kObj, "v 0 0 1e999\n")),
            "memory!/models/quad/quad.obj:1: v: malformed number '1e999'");
  EXPECT_EQ(LoadError(QuadWith(kObj, "s on\n")),
            "memory!/models/quad/quad.obj:1: s: malformed smoothing group 'on'");
  EXPECT_EQ(LoadError(QuadWith(kMtl, "newmtl picture\nKd 1 1 one\n")),
            "memory!/models/quad/quad.mtl:2: Kd: malformed number 'one'");
}

TEST(LoadObjMesh, RefusesMissingFiles) {
  EXPECT_EQ(LoadError(QuadWith(kObj, "")), "memory!/models/quad/quad.obj: no such file");
  EXPECT_EQ(LoadError(QuadWith(kMtl, "")),
            "memory!/models/quad/quad.obj:2: mtllib 'quad.mtl': no such file memory!/models/quad/quad.mtl");
  EXPECT_EQ(LoadError(QuadWith("models/quad/tex/picture.png", "")),
            "memory!/models/quad/quad.mtl:4: map_Kd 'tex/picture.png' is not in the archive "
            "(memory!/models/quad/tex/picture.png)");
  EXPECT_EQ(LoadError(QuadWith(kObj, "v 0 0 0\nf 1 1\n")),
            "memory!/models/quad/quad.obj: no faces with 3 or more corners (1 f statements)");
  const FileMap files = TexturedQuadFiles();
  EXPECT_EQ(InputErrorOf([&] { LoadObjMesh("../quad.obj", MemoryFiles(files)); }),
            "memory!/../quad.obj: not an archive path (absolute, '..' or not normalized)");
}

TEST(LoadObjMesh, RefusesPathsOutsideTheArchive) {
  EXPECT_EQ(LoadError(QuadWith(kObj, "mtllib ../../../etc/quad.mtl\n")),
            "memory!/models/quad/quad.obj:1: mtllib '../../../etc/quad.mtl' is outside the archive (absolute or "
            "'..')");
  EXPECT_EQ(LoadError(QuadWith(kObj, "mtllib /etc/quad.mtl\n")),
            "memory!/models/quad/quad.obj:1: mtllib '/etc/quad.mtl' is outside the archive (absolute or '..')");
  EXPECT_EQ(LoadError(QuadWith(kMtl, "newmtl picture\n\nmap_Kd ../../../secret.png\n")),
            "memory!/models/quad/quad.mtl:3: map_Kd '../../../secret.png' is outside the archive (absolute or '..')");
  EXPECT_EQ(LoadError(QuadWith(kMtl, "newmtl picture\nmap_Kd C:/Documents and Settings/wood.jpg\n")),
            "memory!/models/quad/quad.mtl:2: map_Kd 'C:/Documents and Settings/wood.jpg' is outside the archive "
            "(absolute or '..')");
}

TEST(LoadObjMesh, RefusesOversizedAndUndecodableTextures) {
  EXPECT_EQ(LoadError(QuadWith("models/quad/tex/picture.png", PngHeader(30000, 30000))),
            "memory!/models/quad/quad.mtl:4: map_Kd memory!/models/quad/tex/picture.png: 30000x30000 texture "
            "exceeds the limit of 67108864 pixels");
  ObjLoadOptions small;
  small.max_texture_pixels = 7;
  EXPECT_EQ(LoadError(TexturedQuadFiles(), small),
            "memory!/models/quad/quad.mtl:4: map_Kd memory!/models/quad/tex/picture.png: 4x2 texture exceeds the "
            "limit of 7 pixels");
  EXPECT_EQ(LoadError(QuadWith("models/quad/tex/picture.png", "GIF89a garbage")),
            "memory!/models/quad/quad.mtl:4: map_Kd memory!/models/quad/tex/picture.png: texture cannot be decoded "
            "(not a readable image)");
  EXPECT_EQ(LoadError(QuadWith(kMtl, "newmtl picture\nmap_Kd -clamp on tex/picture.png\n")),
            "memory!/models/quad/quad.mtl:2: map_Kd option -clamp is not supported (only -s and -o)");
}

TEST(LoadObjMesh, SkipsUnavailableTexturesOnRequest) {
  ObjLoadOptions options;
  options.skip_unavailable_textures = true;
  const FileMap files =
      QuadWith(kMtl, "newmtl picture\nKd 0.5 0.5 0.5\nmap_Kd C:/Documents and Settings/wood.jpg\n");
  const ObjLoadResult result = LoadObjMesh(kObj, MemoryFiles(files), options);
  ASSERT_EQ(result.skipped_textures.size(), 1u);
  EXPECT_EQ(result.skipped_textures[0].material, "picture");
  EXPECT_EQ(result.skipped_textures[0].file_name, "C:/Documents and Settings/wood.jpg");
  EXPECT_EQ(result.skipped_textures[0].where, "memory!/models/quad/quad.mtl:3");
  EXPECT_EQ(result.skipped_textures[0].reason, "outside the archive (absolute or '..')");
  EXPECT_TRUE(result.mesh.materials[0].diffuse_texture.empty());
  EXPECT_EQ(result.mesh.materials[0].diffuse_bgr, cv::Vec3f(0.5f, 0.5f, 0.5f));

  const FileMap missing = QuadWith("models/quad/tex/picture.png", "");
  const ObjLoadResult without = LoadObjMesh(kObj, MemoryFiles(missing), options);
  ASSERT_EQ(without.skipped_textures.size(), 1u);
  EXPECT_EQ(without.skipped_textures[0].reason, "not in the archive (memory!/models/quad/tex/picture.png)");
  // A texture that exists but is broken is still an error.
  EXPECT_NE(LoadError(QuadWith("models/quad/tex/picture.png", "junk"), options).find("cannot be decoded"),
            std::string::npos);
}

TEST(ObjLoadOptions, CheckNamesTheField) {
  ObjLoadOptions options;
  options.max_texture_pixels = 0;
  EXPECT_THROW(options.Check(), ConfigError);
  options.max_texture_pixels = kMaxImagePixels + 1;
  EXPECT_THROW(options.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
