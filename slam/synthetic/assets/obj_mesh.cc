#include "slam/synthetic/assets/obj_mesh.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include "slam/core/check.h"
#include "slam/synthetic/assets/archive_path.h"
#include "slam/synthetic/assets/mesh_texture.h"
#include "slam/synthetic/assets/mtl_file.h"
#include "slam/synthetic/assets/obj_text.h"

namespace duskmap {
namespace {

constexpr char kOutsideArchive[] = "outside the archive (absolute or '..')";
constexpr char kNotInArchive[] = "not in the archive";

struct LibraryMaterial {
  MtlMaterial material;
  std::string mtl_path;  // archive path of the MTL that defines it
};

// One OBJ load: the statements in file order, then the materials the faces
// used, with their textures.
class ObjReader {
 public:
  ObjReader(const std::string& obj_path, const MeshFiles& files, const ObjLoadOptions& options)
      : obj_path_(obj_path), files_(files), options_(options), label_(files.Describe(obj_path)) {}

  ObjLoadResult Read() {
    const std::optional<std::string> text = files_.read(obj_path_);
    SLAM_THROW_IF_NOT(InputError, text.has_value()) << label_ << ": no such file";
    ObjTextLines lines(*text);
    std::string_view line;
    int number = 0;
    while (lines.Next(&line, &number)) Statement(line, number);
    SLAM_THROW_IF_NOT(InputError, !result_.mesh.triangles.empty())
        << label_ << ": no faces with 3 or more corners (" << result_.num_faces << " f statements)";
    BuildMaterials();
    return std::move(result_);
  }

 private:
  std::string Where(int line) const { return label_ + ":" + std::to_string(line); }

  void Statement(std::string_view line, int number) {
    std::string_view rest = line;
    const std::string_view keyword = NextObjToken(&rest);
    TriangleMesh& mesh = result_.mesh;
    if (keyword == "v") {
      const Eigen::Vector3d p = Numbers(rest, number, "v", 3, 7);
      mesh.positions.emplace_back(p.cast<float>());
    } else if (keyword == "vt") {
      const Eigen::Vector3d t = Numbers(rest, number, "vt", 1, 3);
      mesh.texcoords.emplace_back(static_cast<float>(t.x()), static_cast<float>(t.y()));
    } else if (keyword == "vn") {
      const Eigen::Vector3d n = Numbers(rest, number, "vn", 3, 3);
      mesh.normals.emplace_back((n.norm() > 0 ? n.normalized() : n).cast<float>());
    } else if (keyword == "f") {
      Face(rest, number);
    } else if (keyword == "usemtl") {
      material_slot_ = MaterialSlot(std::string(TrimObjBlanks(rest)));
    } else if (keyword == "mtllib") {
      MaterialLibraries(rest, number);
    } else if (keyword == "g" || keyword == "o") {
      Part(std::string(TrimObjBlanks(rest)));
    } else if (keyword == "s") {
      SmoothingGroup(TrimObjBlanks(rest), number);
    } else {
      ++result_.num_ignored_statements;
    }
  }

  // `min_count` to `max_count` numbers; the first three (missing ones 0).
  Eigen::Vector3d Numbers(std::string_view rest, int line, const char* keyword, int min_count, int max_count) {
    Eigen::Vector3d values = Eigen::Vector3d::Zero();
    int count = 0;
    for (std::string_view token = NextObjToken(&rest); !token.empty(); token = NextObjToken(&rest)) {
      const std::optional<double> value = ParseObjNumber(token);
      SLAM_THROW_IF_NOT(InputError, value.has_value())
          << Where(line) << ": " << keyword << ": malformed number '" << token << "'";
      if (count < 3) values[count] = *value;
      ++count;
    }
    SLAM_THROW_IF_NOT(InputError, count >= min_count && count <= max_count)
        << Where(line) << ": " << keyword << " needs " << min_count << " to " << max_count << " numbers, got "
        << count;
    return values;
  }

  void Face(std::string_view rest, int line) {
    ++result_.num_faces;
    corners_.clear();
    for (std::string_view token = NextObjToken(&rest); !token.empty(); token = NextObjToken(&rest)) {
      corners_.push_back(Corner(token, line));
    }
    if (corners_.size() < 3) {
      ++result_.num_degenerate_faces;
      return;
    }
    if (material_slot_ < 0) material_slot_ = MaterialSlot("");
    for (size_t i = 1; i + 1 < corners_.size(); ++i) {
      MeshTriangle triangle;
      const std::array<int, 3>* fan[3] = {&corners_[0], &corners_[i], &corners_[i + 1]};
      for (int k = 0; k < 3; ++k) {
        triangle.position[k] = (*fan[k])[0];
        triangle.texcoord[k] = (*fan[k])[1];
        triangle.normal[k] = (*fan[k])[2];
      }
      triangle.material = material_slot_;
      triangle.part = part_;
      triangle.smoothing_group = smoothing_group_;
      result_.mesh.triangles.push_back(triangle);
    }
  }

  // "v", "v/vt", "v//vn" or "v/vt/vn" -> (position, texcoord, normal), -1 = none.
  std::array<int, 3> Corner(std::string_view token, int line) {
    std::array<int, 3> indices = {-1, -1, -1};
    const size_t counts[3] = {result_.mesh.positions.size(), result_.mesh.texcoords.size(),
                              result_.mesh.normals.size()};
    static const char* const kWhat[3] = {"position", "texture coordinate", "normal"};
    SLAM_THROW_IF_NOT(InputError, std::count(token.begin(), token.end(), '/') <= 2)
        << Where(line) << ": malformed face corner '" << token << "'";
    std::string_view rest = token;
    for (int k = 0; k < 3; ++k) {
      const size_t slash = rest.find('/');
      const std::string_view field = rest.substr(0, slash);
      if (!field.empty() || k == 0) {
        const std::optional<long long> index = ParseObjInteger(field);
        SLAM_THROW_IF_NOT(InputError, index.has_value())
            << Where(line) << ": malformed face corner '" << token << "'";
        indices[k] = ResolveIndex(*index, counts[k], kWhat[k], token, line);
      }
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
    }
    return indices;
  }

  int ResolveIndex(long long index, size_t count, const char* what, std::string_view token, int line) const {
    SLAM_THROW_IF_NOT(InputError, index != 0)
        << Where(line) << ": face corner '" << token << "': " << what << " index 0 (OBJ indices start at 1)";
    const long long size = static_cast<long long>(count);
    SLAM_THROW_IF_NOT(InputError, index > 0 ? index <= size : -index <= size)
        << Where(line) << ": face corner '" << token << "': " << what << " index " << index << " is out of range ("
        << count << " defined so far)";
    return static_cast<int>(index > 0 ? index - 1 : size + index);
  }

  int MaterialSlot(const std::string& name) {
    const auto [it, added] = material_slots_.emplace(name, static_cast<int>(material_names_.size()));
    if (added) material_names_.push_back(name);
    return it->second;
  }

  void Part(const std::string& name) {
    if (name.empty()) {
      part_ = -1;
      return;
    }
    std::vector<std::string>& names = result_.mesh.part_names;
    const auto [it, added] = part_slots_.emplace(name, static_cast<int>(names.size()));
    if (added) names.push_back(name);
    part_ = it->second;
  }

  void SmoothingGroup(std::string_view value, int line) {
    if (value == "off") {
      smoothing_group_ = 0;
      return;
    }
    const std::optional<long long> group = ParseObjInteger(value);
    SLAM_THROW_IF_NOT(InputError, group.has_value() && *group >= 0 && *group <= std::numeric_limits<int>::max())
        << Where(line) << ": s: malformed smoothing group '" << value << "'";
    smoothing_group_ = static_cast<int>(*group);
  }

  // mtllib a.mtl [b.mtl ...]; a whole name with blanks when that file exists.
  void MaterialLibraries(std::string_view rest, int line) {
    const std::string whole(TrimObjBlanks(rest));
    const std::optional<std::string> whole_path = ResolveArchiveReference(ArchiveFolder(obj_path_), whole);
    if (whole.find_first_of(" \t") != std::string::npos && whole_path.has_value()) {
      if (std::optional<std::string> text = files_.read(*whole_path)) {
        AddLibrary(*whole_path, *text);
        return;
      }
    }
    for (std::string_view token = NextObjToken(&rest); !token.empty(); token = NextObjToken(&rest)) {
      const std::string name(token);
      const std::optional<std::string> path = ResolveArchiveReference(ArchiveFolder(obj_path_), name);
      SLAM_THROW_IF_NOT(InputError, path.has_value())
          << Where(line) << ": mtllib '" << name << "' is " << kOutsideArchive;
      if (loaded_libraries_.count(*path)) continue;
      const std::optional<std::string> text = files_.read(*path);
      SLAM_THROW_IF_NOT(InputError, text.has_value())
          << Where(line) << ": mtllib '" << name << "': no such file " << files_.Describe(*path);
      AddLibrary(*path, *text);
    }
  }

  void AddLibrary(const std::string& path, const std::string& text) {
    if (!loaded_libraries_.insert(path).second) return;
    for (MtlMaterial& material : ParseMtl(text, files_.Describe(path))) {
      const std::string name = material.name;
      library_.emplace(name, LibraryMaterial{std::move(material), path});  // the first definition wins
    }
  }

  void BuildMaterials() {
    for (const std::string& name : material_names_) {
      Material material;
      material.name = name;
      const auto it = library_.find(name);
      if (it == library_.end()) {
        if (!name.empty()) result_.undefined_materials.push_back(name);
      } else {
        FillMaterial(it->second, &material);
      }
      result_.mesh.materials.push_back(std::move(material));
    }
  }

  void FillMaterial(const LibraryMaterial& source, Material* material) {
    const MtlMaterial& mtl = source.material;
    material->diffuse_bgr = cv::Vec3f(mtl.diffuse_rgb.z(), mtl.diffuse_rgb.y(), mtl.diffuse_rgb.x());
    material->dissolve = mtl.dissolve;
    if (!mtl.diffuse_map.has_value()) return;
    const MtlTextureReference& map = *mtl.diffuse_map;
    material->texture_scale = map.scale;
    material->texture_offset = map.offset;
    const std::string where = files_.Describe(source.mtl_path) + ":" + std::to_string(map.line);
    const std::optional<std::string> path = ResolveArchiveReference(ArchiveFolder(source.mtl_path), map.file_name);
    if (!path.has_value()) {
      Unavailable(mtl.name, map.file_name, where, kOutsideArchive);
      return;
    }
    auto cached = textures_.find(*path);
    if (cached == textures_.end()) {
      const std::optional<std::string> bytes = files_.read(*path);
      if (!bytes.has_value()) {
        Unavailable(mtl.name, map.file_name, where, std::string(kNotInArchive) + " (" + files_.Describe(*path) + ")");
        return;
      }
      result_.texture_file_bytes += static_cast<int64_t>(bytes->size());
      const std::string source_label = where + ": map_Kd " + files_.Describe(*path);
      cached = textures_.emplace(*path, DecodeSrgbTexture(*bytes, source_label, options_.max_texture_pixels)).first;
    }
    material->diffuse_texture = cached->second;
    material->diffuse_texture_path = *path;
  }

  void Unavailable(const std::string& material, const std::string& file_name, const std::string& where,
                   const std::string& reason) {
    SLAM_THROW_IF_NOT(InputError, options_.skip_unavailable_textures)
        << where << ": map_Kd '" << file_name << "' is " << reason;
    result_.skipped_textures.push_back({material, file_name, where, reason});
  }

  const std::string& obj_path_;
  const MeshFiles& files_;
  const ObjLoadOptions& options_;
  const std::string label_;
  ObjLoadResult result_;
  std::vector<std::array<int, 3>> corners_;  // of the face being read
  int material_slot_ = -1;                   // -1 until a usemtl or the first face
  int part_ = -1;
  int smoothing_group_ = 0;
  std::vector<std::string> material_names_;  // used, in order of first use
  std::unordered_map<std::string, int> material_slots_;
  std::unordered_map<std::string, int> part_slots_;
  std::set<std::string> loaded_libraries_;
  std::map<std::string, LibraryMaterial> library_;
  std::map<std::string, cv::Mat> textures_;  // decoded, by archive path
};

}  // namespace

void ObjLoadOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_texture_pixels > 0 && max_texture_pixels <= kMaxImagePixels)
      << "obj_load.max_texture_pixels must be in [1, " << kMaxImagePixels << "], got " << max_texture_pixels;
}

ObjLoadResult LoadObjMesh(const std::string& obj_path, const MeshFiles& files, const ObjLoadOptions& options) {
  options.Check();
  SLAM_THROW_IF_NOT(ConfigError, static_cast<bool>(files.read)) << "LoadObjMesh: MeshFiles::read is not set";
  SLAM_THROW_IF_NOT(InputError, NormalizeArchivePath(obj_path) == obj_path)
      << files.Describe(obj_path) << ": not an archive path (absolute, '..' or not normalized)";
  return ObjReader(obj_path, files, options).Read();
}

}  // namespace duskmap
