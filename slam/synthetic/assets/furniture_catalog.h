// A SweetHome3D furniture catalog (.sh3f): a ZIP archive whose
// PluginFurnitureCatalog.properties lists the pieces (key#N = value per
// piece N) and whose folders hold each piece's OBJ model, MTL materials and
// texture images. Debian's sweethome3d-furniture package installs them in
// /usr/share/sweethome3d/furniture; BlendSwap-CC-0.sh3f (175 pieces, public
// domain) is the default, the other catalogs are CC-BY.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/synthetic/assets/mesh_files.h"

namespace duskmap {

class ZipArchive;

// /usr/share/sweethome3d/furniture/BlendSwap-CC-0.sh3f
std::string DefaultFurnitureCatalogPath();

// The catalog's header keys (without #N).
struct FurnitureCatalogInfo {
  std::string id;           // id=
  std::string name;         // name=
  std::string description;  // description=
  std::string version;      // version=
  std::string license;      // license=
  std::string provider;     // provider=
};

// One piece of furniture, as PluginFurnitureCatalog.properties gives it.
struct FurnitureEntry {
  int index = 0;            // the N of its keys key#N
  std::string id;           // id#N, e.g. "Blend Swap CC-0#bed1"; unique, may be empty
  std::string name;         // name#N, e.g. "Bed"; several pieces may share a name
  std::string category;     // category#N, e.g. "Bedroom"
  std::string creator;      // creator#N
  std::string license;      // license#N, else the catalog's license=
  std::string model_path;   // archive path of its OBJ (model#N without the leading '/')
  bool multi_part_model = false;  // multiPartModel#N: the model's folder holds its MTL and textures
  // width#N, depth#N, height#N: the size the piece is shown at, centimetres.
  Eigen::Vector3d size_cm = Eigen::Vector3d::Zero();
  // modelRotation#N (9 numbers, a row-major 3x3 rotation): turns the OBJ's
  // coordinates, p' = R p, before the model is scaled to size_cm.
  std::optional<Eigen::Matrix3d> model_rotation;

  // The part of the id after its last '#' ("bed1"), or the id.
  std::string Key() const;
};

struct FurnitureCatalogOptions {
  int64_t max_file_bytes = int64_t{256} << 20;  // largest file read from the archive (uncompressed), bytes

  void Check() const;
};

// Const methods may be called from several threads (archive reads are serialised).
class FurnitureCatalog {
 public:
  // Opens and lists a catalog. Throws InputError "<path>: <problem>" when the
  // file is missing (naming the package sweethome3d-furniture and
  // scripts/setup.sh), is not a ZIP archive or is corrupt, has no
  // PluginFurnitureCatalog.properties, or an entry has no model, a model
  // path that leaves the archive or names no file of it, or a size or
  // rotation that is not valid numbers.
  static FurnitureCatalog Open(const std::string& path, const FurnitureCatalogOptions& options = {});

  FurnitureCatalog(FurnitureCatalog&&) noexcept;
  FurnitureCatalog& operator=(FurnitureCatalog&&) noexcept;
  ~FurnitureCatalog();

  const std::string& path() const;
  const FurnitureCatalogInfo& info() const { return info_; }
  // In the order of their N.
  const std::vector<FurnitureEntry>& entries() const { return entries_; }

  // The entry whose id, id key (FurnitureEntry::Key, "bed1") or name (in that
  // order) is `name_or_id`. Throws InputError "<catalog>: no model '<x>'"
  // when none matches, and "<catalog>: model name '<x>' is ambiguous (ids
  // ...)" when several pieces share that name.
  const FurnitureEntry& Find(const std::string& name_or_id) const;

  bool Contains(const std::string& path_in_zip) const;
  // The bytes of a file of the archive (an archive path, no leading '/').
  // Throws InputError "<catalog>!/<file>: <problem>" when it is outside the
  // archive, absent, over max_file_bytes or corrupt.
  std::string ReadFile(const std::string& path_in_zip) const;
  // The catalog's files for LoadObjMesh (obj_mesh.h); valid while the
  // catalog lives.
  MeshFiles Files() const;

 private:
  FurnitureCatalog(std::unique_ptr<ZipArchive> archive, FurnitureCatalogInfo info, std::vector<FurnitureEntry> entries,
                   FurnitureCatalogOptions options);

  std::unique_ptr<ZipArchive> archive_;  // on the heap: Files() keeps pointing at it
  FurnitureCatalogInfo info_;
  std::vector<FurnitureEntry> entries_;
  FurnitureCatalogOptions options_;
};

}  // namespace duskmap
