#include "slam/synthetic/scene/photo_materials.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/assets/mesh_texture.h"

namespace duskmap {
namespace {

constexpr double kPlankWidthM = 0.144;   // as the procedural floor's 18 texels of 8 mm
constexpr double kPlankLengthM = 1.2;    // joints along a plank
constexpr double kTileM = 0.152;         // as the procedural tiles' 19 texels of 8 mm
constexpr int64_t kMaxImagePixels = int64_t{16} << 20;

const std::pair<const char*, TextureKind> kSurfaces[] = {
    {"wood_floor", TextureKind::kWoodFloor}, {"tiles", TextureKind::kTiles},
    {"counter", TextureKind::kCounter},      {"wood", TextureKind::kWood},
    {"fabric", TextureKind::kFabric},
};

// A value in [0, 1) drawn from (seed, stream).
double Uniform(uint64_t seed, uint64_t stream) {
  return static_cast<double>(DeriveSeed(seed, stream) % 1000003) / 1000003.0;
}

// The photo's texel at (column, row) from the offset, repeated.
cv::Vec3f PhotoAt(const cv::Mat& photo, int column, int row) {
  const int c = ((column % photo.cols) + photo.cols) % photo.cols;
  const int r = ((row % photo.rows) + photo.rows) % photo.rows;
  return photo.at<cv::Vec3f>(r, c);
}

cv::Point Offset(const cv::Mat& photo, uint64_t seed, uint64_t stream) {
  return {static_cast<int>(Uniform(seed, 2 * stream) * photo.cols),
          static_cast<int>(Uniform(seed, 2 * stream + 1) * photo.rows)};
}

// Planks along the rows (the photo's rows along the plank), joints between
// planks and every kPlankLengthM at a per-plank phase.
cv::Mat Planks(const cv::Mat& photo, cv::Size size, double texel_m, uint64_t seed, const cv::Vec3f& joint,
               ReliefCanvas& relief) {
  const int plank = TexelCount(kPlankWidthM, texel_m);
  const int length = TexelCount(kPlankLengthM, texel_m);
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < size.width; ++c) {
      const int p = c / plank;
      const int phase = static_cast<int>(Uniform(seed, 0x7068617365ull + p) * length);
      const int segment = (r + phase) / length;
      const bool is_joint = c % plank == 0 || (r + phase) % length == 0;
      if (is_joint) {
        o[c] = joint;
        relief.AddRect(cv::Rect(c, r, 1, 1), -0.003);  // the joints' bevelled grooves
        continue;
      }
      const uint64_t piece = (static_cast<uint64_t>(p) << 20) + static_cast<uint64_t>(segment + 4096);
      const float tone = 0.85f + 0.3f * static_cast<float>(Uniform(seed, 0x746f6e65ull + piece));
      const cv::Point at = Offset(photo, seed, piece);
      o[c] = tone * PhotoAt(photo, at.x + c % plank, at.y + r);
    }
  }
  return out;
}

// Square tiles, each cut from the photo at its own offset, with grout.
cv::Mat Tiles(const cv::Mat& photo, cv::Size size, double texel_m, uint64_t seed, ReliefCanvas& relief) {
  const int tile = TexelCount(kTileM, texel_m);
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < size.width; ++c) {
      if (c % tile == 0 || r % tile == 0) {
        o[c] = cv::Vec3f(0.35f, 0.35f, 0.35f);
        continue;
      }
      const uint64_t piece = (static_cast<uint64_t>(c / tile) << 20) + static_cast<uint64_t>(r / tile);
      const cv::Point at = Offset(photo, seed, piece);
      o[c] = PhotoAt(photo, at.x + c % tile, at.y + r % tile);
    }
  }
  for (int x = 0; x < size.width; x += tile) relief.GrooveColumn(x, 0.003);  // grout, 3 mm back
  for (int y = 0; y < size.height; y += tile) relief.GrooveRow(y, 0.003);
  return out;
}

cv::Mat Repeated(const cv::Mat& photo, cv::Size size, uint64_t seed) {
  const cv::Point at = Offset(photo, seed, 0);
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < size.width; ++c) o[c] = PhotoAt(photo, at.x + c, at.y + r);
  }
  return out;
}

// The creator and licence of the piece whose folder holds `image`.
AssetCredit CreditFor(const FurnitureCatalog& catalog, const std::string& image) {
  namespace fs = std::filesystem;
  AssetCredit credit;
  credit.name = fs::path(image).filename().string();
  credit.source = fs::path(catalog.path()).filename().string() + "#" + image;
  credit.license = catalog.info().license;
  const fs::path folder = fs::path(image).parent_path();
  for (const FurnitureEntry& entry : catalog.entries()) {
    if (fs::path(entry.model_path).parent_path() != folder) continue;
    credit.creator = entry.creator;
    credit.license = entry.license;
    break;
  }
  return credit;
}

}  // namespace

void PhotoMaterialSpec::Check(const std::string& where) const {
  PhotoSurfaceKind(surface);
  SLAM_THROW_IF_NOT(ConfigError, !image.empty()) << where << ".image: empty";
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(width_m) && width_m >= 0.05 && width_m <= 10.0)
      << where << ".width_m must be in [0.05, 10], got " << width_m;
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(texel_m) && texel_m >= 0.001 && texel_m <= 0.05)
      << where << ".texel_m must be in [0.001, 0.05], got " << texel_m;
  SLAM_THROW_IF_NOT(ConfigError, width_m / texel_m >= 8.0)
      << where << ": width_m / texel_m must be at least 8 texels, got " << width_m / texel_m;
}

TextureKind PhotoSurfaceKind(const std::string& surface) {
  for (const auto& [name, kind] : kSurfaces) {
    if (surface == name) return kind;
  }
  std::string names;
  for (const std::string& n : PhotoSurfaceNames()) names += (names.empty() ? "" : ", ") + n;
  throw ConfigError("photo material surface '" + surface + "' is not one of " + names);
}

std::vector<std::string> PhotoSurfaceNames() {
  std::vector<std::string> names;
  for (const auto& entry : kSurfaces) names.push_back(entry.first);
  return names;
}

void CheckPhotoMaterialSpecs(const std::vector<PhotoMaterialSpec>& specs) {
  std::set<std::string> surfaces;
  for (size_t i = 0; i < specs.size(); ++i) {
    const std::string where = "scene.photo_materials[" + std::to_string(i) + "]";
    specs[i].Check(where);
    SLAM_THROW_IF_NOT(ConfigError, surfaces.insert(specs[i].surface).second)
        << where << ".surface: '" << specs[i].surface << "' is given twice";
  }
}

LoadedPhotoMaterials LoadPhotoMaterials(const std::vector<PhotoMaterialSpec>& specs,
                                        const std::string& catalog_path) {
  CheckPhotoMaterialSpecs(specs);
  LoadedPhotoMaterials loaded;
  if (specs.empty()) return loaded;
  const FurnitureCatalog catalog =
      FurnitureCatalog::Open(catalog_path.empty() ? DefaultFurnitureCatalogPath() : catalog_path);
  std::set<std::string> credited;
  for (const PhotoMaterialSpec& spec : specs) {
    const std::string source = catalog.path() + "!/" + spec.image;
    const cv::Mat linear = DecodeSrgbTexture(catalog.ReadFile(spec.image), source, kMaxImagePixels);
    PhotoMaterial material;
    material.kind = PhotoSurfaceKind(spec.surface);
    material.texel_m = spec.texel_m;
    const int width = TexelCount(spec.width_m, spec.texel_m);
    const int height = std::max(2, static_cast<int>(std::lround(width * static_cast<double>(linear.rows) / linear.cols)));
    cv::resize(linear, material.texels, cv::Size(width, height), 0, 0,
               width < linear.cols ? cv::INTER_AREA : cv::INTER_LINEAR);
    loaded.materials.push_back(std::move(material));
    if (credited.insert(spec.image).second) loaded.credits.push_back(CreditFor(catalog, spec.image));
  }
  return loaded;
}

const PhotoMaterial* FindPhotoMaterial(const std::vector<PhotoMaterial>& materials, TextureKind kind) {
  for (const PhotoMaterial& m : materials) {
    if (m.kind == kind) return &m;
  }
  return nullptr;
}

cv::Mat PhotoAlbedo(const PhotoMaterial& material, const TextureRequest& request, cv::Size size,
                    ReliefCanvas& relief) {
  // The photo at the surface's colour: its mean becomes base_bgr.
  const cv::Scalar mean = cv::mean(material.texels);
  cv::Mat photo;
  cv::multiply(material.texels,
               cv::Scalar(request.base_bgr[0] / std::max(mean[0], 1e-4), request.base_bgr[1] / std::max(mean[1], 1e-4),
                          request.base_bgr[2] / std::max(mean[2], 1e-4)),
               photo);
  switch (material.kind) {
    case TextureKind::kWoodFloor:
      return Planks(photo, size, material.texel_m, request.seed, request.base_bgr * 0.35f, relief);
    case TextureKind::kTiles: return Tiles(photo, size, material.texel_m, request.seed, relief);
    default: return Repeated(photo, size, request.seed);
  }
}

}  // namespace duskmap
