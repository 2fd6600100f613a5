#include "slam/synthetic/assets/mesh_texture.h"

#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/image_header.h"

namespace duskmap {
namespace {

// Linear values of the 256 sRGB codes, as a 1x256 CV_32F table for cv::LUT.
const cv::Mat& SrgbToLinearTable() {
  static const cv::Mat table = [] {
    cv::Mat t(1, 256, CV_32F);
    for (int i = 0; i < 256; ++i) t.at<float>(0, i) = SrgbToLinear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

}  // namespace

float SrgbToLinear(float srgb) {
  return srgb <= 0.04045f ? srgb / 12.92f : std::pow((srgb + 0.055f) / 1.055f, 2.4f);
}

cv::Mat DecodeSrgbTexture(const std::string& bytes, const std::string& source, int64_t max_pixels) {
  SLAM_THROW_IF_NOT(InputError, !bytes.empty()) << source << ": texture cannot be decoded (empty file)";
  SLAM_THROW_IF_NOT(InputError, bytes.size() <= static_cast<size_t>(std::numeric_limits<int>::max()))
      << source << ": texture file of " << bytes.size() << " bytes is too large";
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  const std::optional<ImageHeaderSize> declared = ReadImageHeaderSize(data, bytes.size());
  if (declared.has_value()) {
    SLAM_THROW_IF_NOT(InputError, declared->width * declared->height <= max_pixels)
        << source << ": " << declared->width << "x" << declared->height << " texture exceeds the limit of "
        << max_pixels << " pixels";
  }
  const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8U, const_cast<uint8_t*>(data));
  cv::Mat image;
  try {
    image = cv::imdecode(encoded, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION);
  } catch (const cv::Exception& e) {
    SLAM_THROW(InputError) << source << ": texture cannot be decoded (" << e.err << ")";
  }
  SLAM_THROW_IF_NOT(InputError, !image.empty() && image.type() == CV_8UC3)
      << source << ": texture cannot be decoded (not a readable image)";
  SLAM_THROW_IF_NOT(InputError, static_cast<int64_t>(image.total()) <= max_pixels)
      << source << ": " << image.cols << "x" << image.rows << " texture exceeds the limit of " << max_pixels
      << " pixels";
  cv::Mat linear;
  cv::LUT(image, SrgbToLinearTable(), linear);
  return linear;
}

}  // namespace duskmap
