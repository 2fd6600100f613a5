// Procedural, seeded surface textures: the albedo (linear BGR, CV_32FC3 in
// [0, 1]) and, on request, the relief height drawn with it (relief.h). The
// texture size in texels is the surface size divided by the texel size.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

struct PhotoMaterial;  // photo_materials.h

enum class TextureKind {
  kPaint,     // plain wall paint with subtle low-frequency noise (weakly textured)
  kCeiling,   // nearly uniform white
  kWoodFloor, // planks with grain
  kWood,      // furniture wood
  kCounter,   // kitchen worktop: drawn as kWood unless a photo material replaces it
  kTiles,     // square tiles with grout lines
  kFabric,    // woven fabric
  kRug,       // patterned rug
  kBooks,     // a shelf of book spines
  kPicture,   // framed picture: shapes and gradients
  kPoster,    // poster: shapes and text
  kDocking,   // the highly textured docking picture
  kDoor,      // painted door panel
  kWindow,    // sky and outdoor silhouettes behind mullions (shown emissive)
  kLampShade, // translucent shade
  kCabinet,   // cabinet or wardrobe front: door panels with edges and handles
  kRadiator,  // painted radiator: vertical fins
  kCurtain,   // patterned curtain fabric with vertical folds
  kScreen,    // switched-off TV or monitor: dark glass in a bezel
  kPackaging, // printed packaging or covers: labels, stripes, text (boxes, jars, magazines)
  kWallpaper, // patterned wallpaper: a scattered, non-repeating motif
  kSwitch,    // wall switch or socket plate
  kClock,     // wall clock face with ticks and hands
  kFoliage,   // house-plant leaves
};

struct TextureRequest {
  TextureKind kind = TextureKind::kPaint;
  double size_u_m = 1.0;
  double size_v_m = 1.0;
  cv::Vec3f base_bgr = cv::Vec3f(0.6f, 0.6f, 0.6f);  // main colour (linear)
  uint64_t seed = 0;
  double relief_scale = 0.0;  // multiplies the material's relief heights (relief.h); 0 = flat
};

struct SurfaceTexture {
  cv::Mat albedo;    // CV_32FC3
  cv::Mat height_m;  // CV_32F, the albedo's size; empty when flat
};

// Texel size in metres used for each kind (finer for pictures and books).
double TexelSizeM(TextureKind kind);

// Texels across `size_m` at `texel_m` each, rounded, at least 2.
int TexelCount(double size_m, double texel_m);

// Generates the texture. `user_images` (optional) replaces the content of
// pictures and posters with the user's images, chosen by seed. `photo`
// (optional, of the request's kind) draws the albedo from a photographic
// material at its own texel size (photo_materials.h). The albedo
// does not depend on relief_scale (the relief draws from its own stream); the
// height is empty for flat kinds (prints, screens, windows, lamp shades) and
// for relief_scale 0.
SurfaceTexture MakeTexture(const TextureRequest& request, const std::vector<cv::Mat>& user_images,
                           const PhotoMaterial* photo = nullptr);

// Loads every readable .png/.jpg/.jpeg in `folder` (sorted by name); throws
// InputError naming the folder when it is missing or holds no image.
std::vector<cv::Mat> LoadUserTextures(const std::string& folder);

}  // namespace duskmap
