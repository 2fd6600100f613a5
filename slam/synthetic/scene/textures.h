// Procedural, seeded surface textures: the albedo (linear BGR, CV_32FC3 in
// [0, 1]) and, on request, the relief height drawn with it (relief.h). The
// texture size in texels is the surface size divided by the texel size.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/synthetic/scene/texture_request.h"

namespace duskmap {

struct PhotoMaterial;  // photo_materials.h

struct SurfaceTexture {
  cv::Mat albedo;    // CV_32FC3
  cv::Mat height_m;  // CV_32F, the albedo's size; empty when flat
};

// Texel size in metres used for each kind (finer for pictures and books).
double TexelSizeM(TextureKind kind);

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
