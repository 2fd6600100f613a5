// A mip-mapped texture for the furniture meshes' photographic textures: a
// box-filtered pyramid of a CV_32FC3 linear-BGR image and trilinear sampling
// at a pixel's footprint, so that a texture seen from afar averages its
// texels instead of aliasing. Deterministic, no state besides the levels.
//
// Texture coordinates follow OBJ (and TriangleMesh::texcoords): u to the
// right, v UP, so (u, v) = (0, 0) is the image's bottom-left corner and
// v = 1 its top edge (image row 0). Texel centres lie at
// u = (col + 0.5) / width, v = 1 - (row + 0.5) / height. Addressing wraps
// around (repeat): u and u + 1 sample the same texel.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

class MipTexture {
 public:
  MipTexture() = default;  // empty(): Sample must not be called
  // Builds the pyramid of `image_bgr` (CV_32FC3, any size >= 1x1; throws
  // InputError otherwise). Level 0 shares the image's pixels (no copy):
  // do not modify the image afterwards. Each next level has half the size
  // rounded down (at least 1) and averages the texels under each of its
  // texels, area-weighted (an odd size splits a source texel between two),
  // so every level keeps the image's mean; the last level is 1x1.
  explicit MipTexture(const cv::Mat& image_bgr);

  bool empty() const { return levels_.empty(); }
  int num_levels() const { return static_cast<int>(levels_.size()); }
  const cv::Mat& level(int index) const { return levels_.at(static_cast<size_t>(index)); }
  int width() const { return empty() ? 0 : levels_[0].cols; }
  int height() const { return empty() ? 0 : levels_[0].rows; }

  // The trilinear sample at texture coordinates (u, v) for a pixel that
  // covers `footprint_texels` level-0 texels across (FootprintTexels): the
  // level of detail log2(footprint), clamped to [0, last level], picks the
  // two nearest levels, each sampled bilinearly with wrap-around, blended by
  // its fraction. A footprint <= 1 (or NaN) samples level 0 alone. A
  // non-finite u or v reads as 0.
  cv::Vec3f Sample(double u, double v, double footprint_texels) const;

  // The bilinear, wrap-around sample of one level.
  cv::Vec3f SampleLevel(int level, double u, double v) const;

 private:
  std::vector<cv::Mat> levels_;  // CV_32FC3, level 0 first
};

// A pixel's footprint in level-0 texels from the screen-space derivatives
// of its texture coordinates (per pixel, along image x and y): the longer of
// the two derivative vectors measured in texels,
// max(|(du_dx * width, dv_dx * height)|, |(du_dy * width, dv_dy * height)|).
double FootprintTexels(double du_dx, double dv_dx, double du_dy, double dv_dy, int width, int height);

}  // namespace duskmap
