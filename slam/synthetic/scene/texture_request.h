// What a procedural or photographic texture is asked for: the surface's
// kind, size, colour, seed and relief (textures.h draws it, photo_materials.h
// draws the photographic kinds), and the texel count of a size. Shared by
// both so that neither includes the other.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace duskmap {

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

// Texels across `size_m` at `texel_m` each, rounded, at least 2.
int TexelCount(double size_m, double texel_m);

}  // namespace duskmap
