// Wavefront OBJ models with their MTL materials and textures, as the
// SweetHome3D furniture catalogs hold them, loaded into a TriangleMesh.
// Files are read through MeshFiles (a catalog's ZIP, or memory in tests),
// by archive paths: an OBJ's mtllib names resolve against the OBJ's folder,
// an MTL's map_Kd names against the MTL's folder, and none may leave the
// archive.
//
// Read: v (x y z; a w or vertex colours after them are ignored), vt (u [v]),
// vn, f (any number of corners, fan-triangulated as (0, i, i + 1); v, v/vt,
// v//vn or v/vt/vn; positive indices count from 1 among the vertices defined
// so far, negative ones back from the last defined), usemtl, mtllib (several
// names per line), g and o (the triangle's part), s (its smoothing group).
// Skipped and counted: l, p and free-form geometry (curv, surf...) and any
// other statement. Positions keep the OBJ's units and axes (SweetHome3D: y
// up, the model's front towards +z); furniture_placement.h scales and turns
// them into the scene's frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slam/io/image_header.h"
#include "slam/synthetic/assets/mesh_files.h"
#include "slam/synthetic/raster/triangle_mesh.h"

namespace duskmap {

struct ObjLoadOptions {
  // A map_Kd whose file is not in the archive, or whose name leaves it
  // (absolute, ".."), is skipped: the material keeps its Kd and the texture
  // is listed in ObjLoadResult::skipped_textures, instead of failing the
  // load. Real catalogs need it: BlendSwap-CC-0's beds name textures as
  // "C:/Documents and Settings/...". The file is never read either way.
  bool skip_unavailable_textures = false;
  int64_t max_texture_pixels = kMaxImagePixels;  // largest texture, pixels, checked before decoding

  void Check() const;
};

// A texture left out under ObjLoadOptions::skip_unavailable_textures.
struct SkippedTexture {
  std::string material;
  std::string file_name;  // as the MTL names it
  std::string where;      // "<mtl>:<line>"
  std::string reason;     // "not in the archive", "outside the archive (absolute or '..')"
};

struct ObjLoadResult {
  TriangleMesh mesh;  // materials: those its faces use, in order of first use
  int num_faces = 0;                // f statements read
  int num_degenerate_faces = 0;     // f statements with fewer than 3 corners, skipped
  int num_ignored_statements = 0;   // l, p, free-form geometry and unknown statements
  // usemtl names no MTL defines; their faces get a default material of that
  // name (Kd 0.8 grey, no texture).
  std::vector<std::string> undefined_materials;
  std::vector<SkippedTexture> skipped_textures;
  int64_t texture_file_bytes = 0;   // bytes of the texture files read (encoded), each once
};

// Loads the OBJ at `obj_path` (an archive path) with its materials and
// textures. Throws InputError, one line naming the file (and line) and the
// problem: the OBJ or an MTL it names is missing, or an MTL's name leaves
// the archive; a malformed number or face corner, an index that is 0 or
// out of range; an MTL error (mtl_file.h); a texture that is missing or
// named outside the archive (unless skip_unavailable_textures), larger than
// max_texture_pixels or undecodable; an OBJ without faces.
ObjLoadResult LoadObjMesh(const std::string& obj_path, const MeshFiles& files, const ObjLoadOptions& options = {});

}  // namespace duskmap
