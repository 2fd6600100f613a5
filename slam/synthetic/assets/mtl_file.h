// The materials of an MTL file as written, before their textures are read
// (obj_mesh.h resolves and decodes them). Read: newmtl, Kd (r g b, or one
// value for all three), d, Tr (taken as 1 - d), and map_Kd with its -s and
// -o options; every other statement (Ka, Ks, Ns, illum, other maps...) is
// skipped.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace duskmap {

struct MtlTextureReference {
  std::string file_name;  // as written (may hold blanks), resolved by the reader
  Eigen::Vector2f scale = Eigen::Vector2f::Ones();    // -s u v
  Eigen::Vector2f offset = Eigen::Vector2f::Zero();   // -o u v
  int line = 0;           // where the MTL names it
};

struct MtlMaterial {
  std::string name;
  Eigen::Vector3f diffuse_rgb = Eigen::Vector3f::Constant(0.8f);  // Kd (the MTL's order, r g b)
  std::optional<float> dissolve;                                  // d, or 1 - Tr; d wins when both
  std::optional<MtlTextureReference> diffuse_map;                 // map_Kd
  int line = 0;                                                   // its newmtl line
};

// The materials of the MTL text `text`, in file order; a name defined twice
// keeps its first definition. `source` names the file in messages. Throws
// InputError "<source>:<line>: <problem>" for a malformed or out-of-range
// number, a statement before the first newmtl, a newmtl without a name, a
// Kd given as spectral or xyz, a map_Kd without a file name or with an
// option other than -s and -o.
std::vector<MtlMaterial> ParseMtl(const std::string& text, const std::string& source);

}  // namespace duskmap
