#include "slam/io/image_header.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

constexpr uint8_t kPngMagic[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
// Bytes read up front: enough for PNG's IHDR, BMP's headers and a PNM header with comments.
constexpr size_t kHeadBytes = 4096;
// JPEG marker segments visited before giving up (each payload is at most
// 64 kB, so real files reach their frame header within a few dozen).
constexpr int kMaxJpegMarkers = 100000;

int64_t ReadBigEndian(const uint8_t* p, int bytes) {
  int64_t value = 0;
  for (int i = 0; i < bytes; ++i) value = (value << 8) | p[i];
  return value;
}

bool IsPng(const uint8_t* data, size_t size) {
  return size >= 8 && std::memcmp(data, kPngMagic, 8) == 0;
}

bool IsJpeg(const uint8_t* data, size_t size) {
  return size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF;
}

bool IsPnm(const uint8_t* data, size_t size) {
  return size >= 3 && data[0] == 'P' && data[1] >= '1' && data[1] <= '6' &&
         std::strchr(" \t\r\n#", data[2]) != nullptr && data[2] != '\0';
}

// BMP: "BM", then the DIB header's size at 14: 12 for the old core header
// (16-bit width and height at 18), else 32-bit width and height at 18 and 22,
// little-endian, the height negative for a top-down image.
bool IsBmp(const uint8_t* data, size_t size) { return size >= 3 && data[0] == 'B' && data[1] == 'M'; }

int64_t ReadLittleEndian(const uint8_t* p, int bytes) {
  uint64_t value = 0;
  for (int i = bytes - 1; i >= 0; --i) value = (value << 8) | p[i];
  return static_cast<int64_t>(value);
}

std::optional<ImageHeaderSize> BmpSize(const uint8_t* data, size_t size) {
  if (size < 26) return std::nullopt;
  const int64_t dib_size = ReadLittleEndian(data + 14, 4);
  // The DIB header sizes BMP files use; other bytes after "BM" are no BMP
  // header (the decoder then judges the file).
  if (dib_size != 12 && dib_size != 40 && dib_size != 52 && dib_size != 56 && dib_size != 64 &&
      dib_size != 108 && dib_size != 124) {
    return std::nullopt;
  }
  if (dib_size == 12) {
    return ImageHeaderSize{ReadLittleEndian(data + 18, 2), ReadLittleEndian(data + 20, 2)};
  }
  const int64_t width = static_cast<int32_t>(ReadLittleEndian(data + 18, 4));
  const int64_t height = static_cast<int32_t>(ReadLittleEndian(data + 22, 4));
  // A negative width is no image: it is judged as too large.
  return ImageHeaderSize{width < 0 ? int64_t{1} << 40 : width, height < 0 ? -height : height};
}

std::optional<ImageHeaderSize> PngSize(const uint8_t* data, size_t size) {
  if (size < 24 || std::memcmp(data + 12, "IHDR", 4) != 0) return std::nullopt;
  return ImageHeaderSize{ReadBigEndian(data + 16, 4), ReadBigEndian(data + 20, 4)};
}

// PNM: magic, then width and height as decimal numbers separated by
// whitespace, with '#' comments running to the end of their line.
std::optional<ImageHeaderSize> PnmSize(const uint8_t* data, size_t size) {
  size_t i = 2;
  int64_t values[2] = {0, 0};
  for (int64_t& value : values) {
    while (i < size) {
      if (data[i] == '#') {
        while (i < size && data[i] != '\n' && data[i] != '\r') ++i;
      } else if (std::strchr(" \t\r\n\v\f", data[i]) != nullptr && data[i] != '\0') {
        ++i;
      } else {
        break;
      }
    }
    if (i >= size || data[i] < '0' || data[i] > '9') return std::nullopt;
    while (i < size && data[i] >= '0' && data[i] <= '9') {
      // Saturates far above the limit instead of overflowing.
      value = std::min<int64_t>(value * 10 + (data[i] - '0'), int64_t{1} << 40);
      ++i;
    }
    if (i >= size) return std::nullopt;  // the number may go on past what was read
  }
  return ImageHeaderSize{values[0], values[1]};
}

// Walks the JPEG marker segments after SOI up to the first frame header
// (SOF0-SOF15 except DHT C4, JPG C8 and DAC CC). `read(offset, out, n)` reads
// n bytes at offset and returns false past the end.
template <typename ReadAt>
std::optional<ImageHeaderSize> JpegSize(const ReadAt& read) {
  uint64_t i = 2;
  for (int step = 0; step < kMaxJpegMarkers; ++step) {
    uint8_t marker[4];
    if (!read(i, marker, 2) || marker[0] != 0xFF) return std::nullopt;
    const uint8_t code = marker[1];
    if (code == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    if (code == 0x01 || (code >= 0xD0 && code <= 0xD7)) {  // TEM, RSTn: no length
      i += 2;
      continue;
    }
    if (code == 0xD8 || code == 0xD9 || code == 0xDA) return std::nullopt;  // no frame header
    if (!read(i + 2, marker + 2, 2)) return std::nullopt;
    const int64_t length = ReadBigEndian(marker + 2, 2);
    if (length < 2) return std::nullopt;
    const bool start_of_frame =
        code >= 0xC0 && code <= 0xCF && code != 0xC4 && code != 0xC8 && code != 0xCC;
    if (start_of_frame) {
      uint8_t frame[5];  // precision, height, width
      if (length < 7 || !read(i + 4, frame, 5)) return std::nullopt;
      return ImageHeaderSize{ReadBigEndian(frame + 3, 2), ReadBigEndian(frame + 1, 2)};
    }
    i += 2 + static_cast<uint64_t>(length);
  }
  return std::nullopt;
}

}  // namespace

bool WithinPixelLimit(const ImageHeaderSize& size) {
  return size.width >= 0 && size.height >= 0 && size.width <= kMaxImagePixels &&
         size.height <= kMaxImagePixels && size.width * size.height <= kMaxImagePixels;
}

std::optional<ImageHeaderSize> ReadImageHeaderSize(const uint8_t* data, size_t size) {
  if (IsPng(data, size)) return PngSize(data, size);
  if (IsPnm(data, size)) return PnmSize(data, size);
  if (IsBmp(data, size)) return BmpSize(data, size);
  if (IsJpeg(data, size)) {
    return JpegSize([&](uint64_t offset, uint8_t* out, size_t n) {
      if (offset > size || n > size - offset) return false;
      std::memcpy(out, data + offset, n);
      return true;
    });
  }
  return std::nullopt;
}

std::optional<ImageHeaderSize> ReadImageFileHeaderSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in.good()) return std::nullopt;
  uint8_t head[kHeadBytes];
  in.read(reinterpret_cast<char*>(head), sizeof(head));
  const size_t got = static_cast<size_t>(in.gcount());
  if (!IsJpeg(head, got)) return ReadImageHeaderSize(head, got);
  return JpegSize([&](uint64_t offset, uint8_t* out, size_t n) {
    if (offset + n <= got) {
      std::memcpy(out, head + offset, n);
      return true;
    }
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return in.good() && static_cast<size_t>(in.gcount()) == n;
  });
}

void CheckImageFilePixelLimit(const std::string& path) {
  {
    std::ifstream in(path, std::ios::binary);
    uint8_t magic[8] = {};
    in.read(reinterpret_cast<char*>(magic), sizeof(magic));
    const size_t got = static_cast<size_t>(in.gcount());
    // Other formats (TIFF, BMP, WebP, EXR, ...) would reach a decoder whose
    // allocation nothing checked first; they are refused by name instead.
    SLAM_THROW_IF_NOT(InputError, got < 3 || IsPng(magic, got) || IsJpeg(magic, got) || IsPnm(magic, got) ||
                                      IsBmp(magic, got))
        << path << ": not a PNG, JPEG, PNM or BMP image (only these are read: their size is checked before decoding)";
  }
  const std::optional<ImageHeaderSize> size = ReadImageFileHeaderSize(path);
  if (!size) return;
  SLAM_THROW_IF_NOT(InputError, WithinPixelLimit(*size))
      << path << ": " << size->width << "x" << size->height << " image exceeds the "
      << (kMaxImagePixels >> 20) << "-Mpixel limit";
}

std::string ImageTruncation(bool is_jpeg, bool is_png, const uint8_t* tail, size_t tail_size) {
  if (is_jpeg) {
    for (size_t i = 0; i + 1 < tail_size; ++i) {
      if (tail[i] == 0xFF && tail[i + 1] == 0xD9) return "";
    }
    return "JPEG is truncated (no end-of-image marker)";
  }
  // A PNG ends with the IEND chunk: length 0, "IEND", CRC (12 bytes).
  if (is_png && (tail_size < 12 || std::memcmp(tail + tail_size - 8, "IEND", 4) != 0)) {
    return "PNG is truncated (no IEND chunk)";
  }
  return "";
}

void CheckImageFileBeforeDecoding(const std::string& path) {
  RefuseNonRegularFile(path);
  CheckImageFilePixelLimit(path);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in.good()) return;  // missing or unreadable: the decoder's caller names it
  const std::streamoff size = in.tellg();
  uint8_t head[8] = {};
  uint8_t tail[kImageTrailerSearchBytes] = {};
  in.seekg(0);
  in.read(reinterpret_cast<char*>(head), sizeof(head));
  const size_t head_size = static_cast<size_t>(in.gcount());
  const std::streamoff tail_size =
      std::min<std::streamoff>(size, static_cast<std::streamoff>(sizeof(tail)));
  in.clear();
  in.seekg(size - tail_size);
  in.read(reinterpret_cast<char*>(tail), tail_size);
  SLAM_THROW_IF_NOT(InputError, in.gcount() == tail_size) << path << ": cannot read its last bytes";
  const std::string problem = ImageTruncation(IsJpeg(head, head_size), IsPng(head, head_size),
                                              tail, static_cast<size_t>(tail_size));
  SLAM_THROW_IF_NOT(InputError, problem.empty()) << path << ": " << problem;
}

}  // namespace duskmap
