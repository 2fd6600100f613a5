#include "slam/datasets/image_blob.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/datasets/rvl_codec.h"
#include "slam/io/image_header.h"

namespace duskmap {
namespace {

constexpr uint8_t kPngMagic[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};

const char* CodecName(BlobCodec codec) {
  switch (codec) {
    case BlobCodec::kJpeg: return "JPEG";
    case BlobCodec::kPng: return "PNG";
    case BlobCodec::kRvl: return "RVL";
    case BlobCodec::kUnknown: break;
  }
  return "unknown";
}

// Checks that the blob is complete before handing it to the decoder (which
// would otherwise print warnings and return a partially grey image); the
// same test as the image files' (slam/io/image_header.h).
void CheckComplete(const uint8_t* data, size_t size, BlobCodec codec, const std::string& where) {
  const size_t tail = std::min(size, kImageTrailerSearchBytes);
  const std::string problem = ImageTruncation(codec == BlobCodec::kJpeg, codec == BlobCodec::kPng,
                                              data + size - tail, tail);
  SLAM_THROW_IF_NOT(InputError, problem.empty() && (codec != BlobCodec::kJpeg || size > 4))
      << where << ": " << (problem.empty() ? "JPEG is truncated (no end-of-image marker)" : problem);
}

// Images larger than kMaxImagePixels (slam/io/image_header.h, shared with the
// file readers) are refused before decoding: a header can declare any size,
// and the decoder would allocate it (found by fuzzing: a 3-kB blob declaring
// 2.6 GB of pixels).

cv::Mat Decode(const uint8_t* data, size_t size, BlobCodec codec, const std::string& where) {
  CheckComplete(data, size, codec, where);
  const std::optional<ImageHeaderSize> declared = ReadImageHeaderSize(data, size);
  SLAM_THROW_IF_NOT(InputError, !declared || WithinPixelLimit(*declared))
      << where << ": " << CodecName(codec) << " declares " << declared->width << "x"
      << declared->height << " pixels, more than the " << kMaxImagePixels << "-pixel limit";
  const cv::Mat buffer(1, static_cast<int>(size), CV_8UC1, const_cast<uint8_t*>(data));
  cv::Mat image;
  try {
    image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    image.release();
  }
  SLAM_THROW_IF_NOT(InputError, !image.empty())
      << where << ": " << CodecName(codec) << " image does not decode";
  return image;
}

}  // namespace

BlobCodec SniffBlobCodec(const uint8_t* data, size_t size) {
  if (size >= 2 && data[0] == 0xFF && data[1] == 0xD8) return BlobCodec::kJpeg;
  if (size >= 8 && std::memcmp(data, kPngMagic, 8) == 0) return BlobCodec::kPng;
  if (IsRvlBlob(data, size)) return BlobCodec::kRvl;
  return BlobCodec::kUnknown;
}

cv::Mat DecodeColorBlob(const uint8_t* data, size_t size, const std::string& where) {
  const BlobCodec codec = SniffBlobCodec(data, size);
  SLAM_THROW_IF_NOT(InputError, codec == BlobCodec::kJpeg || codec == BlobCodec::kPng)
      << where << ": colour image is neither JPEG nor PNG (" << size << " bytes)";
  const cv::Mat image = Decode(data, size, codec, where);
  SLAM_THROW_IF_NOT(InputError, image.depth() == CV_8U)
      << where << ": colour image is not 8-bit (OpenCV type " << image.type() << ")";
  cv::Mat bgr;
  switch (image.channels()) {
    case 1: cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR); break;
    case 3: bgr = image; break;
    case 4: cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR); break;
    default:
      SLAM_THROW(InputError) << where << ": colour image has " << image.channels()
                             << " channels";
  }
  return bgr;
}

cv::Mat DepthMillimetresToMetres(const cv::Mat& depth_mm) {
  SLAM_CHECK(depth_mm.type() == CV_16UC1);
  cv::Mat depth_m;
  depth_mm.convertTo(depth_m, CV_32F, 0.001);
  return depth_m;
}

cv::Mat DecodeDepthBlob(const uint8_t* data, size_t size, const std::string& where) {
  const BlobCodec codec = SniffBlobCodec(data, size);
  if (codec == BlobCodec::kRvl) return DepthMillimetresToMetres(DecodeRvlBlob(data, size, where));
  SLAM_THROW_IF_NOT(InputError, codec == BlobCodec::kPng)
      << where << ": depth of unexpected type: " << CodecName(codec)
      << " (expected RVL or PNG)";
  const cv::Mat image = Decode(data, size, codec, where);
  if (image.type() == CV_16UC1) return DepthMillimetresToMetres(image);
  SLAM_THROW_IF_NOT(InputError, image.type() == CV_8UC4)
      << where << ": depth of unexpected type: PNG with " << image.channels() << " channel(s) of "
      << (image.depth() == CV_8U ? "8" : "16") << " bits (expected 16-bit mm or float32 as 8UC4)";
  // Each BGRA pixel holds the 4 little-endian bytes of one float32 (metres).
  cv::Mat depth_m(image.rows, image.cols, CV_32FC1);
  for (int r = 0; r < image.rows; ++r) {
    std::memcpy(depth_m.ptr<float>(r), image.ptr<uint8_t>(r), sizeof(float) * image.cols);
  }
  for (auto it = depth_m.begin<float>(); it != depth_m.end<float>(); ++it) {
    if (!std::isfinite(*it) || *it < 0.0f) *it = 0.0f;
  }
  return depth_m;
}

}  // namespace duskmap
