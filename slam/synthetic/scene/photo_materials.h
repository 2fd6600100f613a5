// Photographic materials: a surface class of the apartment (its wood floors,
// tiles, kitchen counter, furniture wood or fabric) drawn from a photo of
// the furniture catalog (a wood veneer, a granite slab, a weave) instead of
// procedural noise. The photo gives the pattern at its physical size; the
// scene's own colour for the surface is kept as the mean, so a material
// changes the detail a camera sees and not the room's reflectance. Floors
// are laid as planks and tiles as tiles, each cut from the photo at its own
// offset; the other classes repeat the photo.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/synthetic/scene/relief.h"
#include "slam/synthetic/scene/scene.h"
#include "slam/synthetic/scene/texture_request.h"

namespace duskmap {

// One photographic material as a config gives it:
//   {"surface": "wood_floor", "image": "blendswap-cc-0/lowerCabinet/american_oak.jpg",
//    "width_m": 0.6, "texel_m": 0.004}
struct PhotoMaterialSpec {
  std::string surface;   // "wood_floor", "tiles", "counter", "wood" or "fabric"
  std::string image;     // archive path of a JPEG or PNG in the furniture catalog
  double width_m = 0.6;  // the photo's width on the surface, metres
  double texel_m = 0.004;  // the texture's texel on the surface, metres

  void Check(const std::string& where) const;  // throws ConfigError "<where>.<field>: problem"
};

// Checks each spec (its index in `where`: "scene.photo_materials[i]") and that
// no surface is given twice; throws ConfigError.
void CheckPhotoMaterialSpecs(const std::vector<PhotoMaterialSpec>& specs);

// The surface classes a photo can replace, as TextureKinds.
TextureKind PhotoSurfaceKind(const std::string& surface);  // throws ConfigError for an unknown name
std::vector<std::string> PhotoSurfaceNames();

// A photo loaded for a surface: linear BGR resampled to texel_m.
struct PhotoMaterial {
  TextureKind kind = TextureKind::kWoodFloor;
  cv::Mat texels;  // CV_32FC3, linear BGR; one texel = texel_m on the surface
  double texel_m = 0.004;
};

struct LoadedPhotoMaterials {
  std::vector<PhotoMaterial> materials;
  std::vector<AssetCredit> credits;  // one per distinct image
};

// Checks the specs (CheckPhotoMaterialSpecs), opens the catalog ("" = the
// default, furniture_catalog.h) and reads, decodes and resamples each image.
// The credit of an image is the creator and licence of the catalog piece
// whose folder holds it, else the catalog's licence. Throws ConfigError for
// a bad spec and InputError "<catalog>!/<image>: problem" for an image that
// is absent, not an image or corrupt (and the catalog's own errors).
LoadedPhotoMaterials LoadPhotoMaterials(const std::vector<PhotoMaterialSpec>& specs,
                                        const std::string& catalog_path);

// The material for `kind`, or nullptr.
const PhotoMaterial* FindPhotoMaterial(const std::vector<PhotoMaterial>& materials, TextureKind kind);

// The albedo of a surface of `size` texels of material.texel_m (columns
// along u; MakeTexture sizes it from the request), from the photo: planks
// 0.144 m wide with joints along the rows for wood floors, 0.152 m tiles
// with grout for tiles, the repeated photo otherwise; each plank segment,
// tile or surface takes the photo at an offset drawn from request.seed.
// Scaled per channel so that its mean is request.base_bgr. Joints and grout
// are cut into `relief` (when enabled) as the procedural materials cut them.
cv::Mat PhotoAlbedo(const PhotoMaterial& material, const TextureRequest& request, cv::Size size,
                    ReliefCanvas& relief);

}  // namespace duskmap
