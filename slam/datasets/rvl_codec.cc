#include "slam/datasets/rvl_codec.h"

#include <cstring>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr char kMagic[] = "DEPTHRVL";
constexpr size_t kHeaderBytes = 16;

uint32_t ReadLe32(const uint8_t* p) {
  return uint32_t{p[0]} | (uint32_t{p[1]} << 8) | (uint32_t{p[2]} << 16) |
         (uint32_t{p[3]} << 24);
}

void WriteLe32(uint32_t v, std::vector<uint8_t>* out) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

class NibbleReader {
 public:
  NibbleReader(const uint8_t* words, size_t num_words, const std::string& where)
      : words_(words), num_nibbles_(num_words * 8), where_(where) {}

  uint32_t Nibble() {
    SLAM_THROW_IF_NOT(InputError, next_ < num_nibbles_)
        << where_ << ": RVL payload is truncated";
    const uint32_t word = ReadLe32(words_ + 4 * (next_ / 8));
    const uint32_t nibble = (word >> (28 - 4 * (next_ % 8))) & 0xFu;
    ++next_;
    return nibble;
  }
  // A variable-length unsigned integer (at most 32 bits: 11 groups).
  uint32_t Vle() {
    uint64_t value = 0;
    for (int shift = 0;; shift += 3) {
      SLAM_THROW_IF_NOT(InputError, shift <= 30) << where_ << ": RVL integer is too long";
      const uint32_t nibble = Nibble();
      value |= uint64_t{nibble & 7u} << shift;
      if (!(nibble & 8u)) break;
    }
    SLAM_THROW_IF_NOT(InputError, value <= 0xFFFFFFFFull) << where_ << ": RVL integer overflows";
    return static_cast<uint32_t>(value);
  }

 private:
  const uint8_t* words_;
  size_t num_nibbles_;
  size_t next_ = 0;
  const std::string& where_;
};

class NibbleWriter {
 public:
  explicit NibbleWriter(std::vector<uint8_t>* out) : out_(out) {}
  void Vle(uint32_t value) {
    do {
      uint32_t nibble = value & 7u;
      value >>= 3;
      if (value) nibble |= 8u;
      word_ = (word_ << 4) | nibble;
      if (++count_ == 8) Flush();
    } while (value);
  }
  void Finish() {
    if (count_ == 0) return;
    word_ <<= 4 * (8 - count_);
    Flush();
  }

 private:
  void Flush() {
    WriteLe32(word_, out_);
    word_ = 0;
    count_ = 0;
  }
  std::vector<uint8_t>* out_;
  uint32_t word_ = 0;
  int count_ = 0;
};

}  // namespace

bool IsRvlBlob(const uint8_t* data, size_t size) {
  return size >= 8 && std::memcmp(data, kMagic, 8) == 0;
}

cv::Mat DecodeRvlBlob(const uint8_t* data, size_t size, const std::string& where) {
  SLAM_THROW_IF_NOT(InputError, IsRvlBlob(data, size)) << where << ": not an RVL blob";
  SLAM_THROW_IF_NOT(InputError, size >= kHeaderBytes) << where << ": RVL header is truncated";
  const uint32_t width = ReadLe32(data + 8);
  const uint32_t height = ReadLe32(data + 12);
  SLAM_THROW_IF_NOT(InputError, width > 0 && height > 0 &&
                                    int64_t{width} * height <= kMaxRvlPixels)
      << where << ": RVL image size " << width << "x" << height << " is out of range";
  SLAM_THROW_IF_NOT(InputError, (size - kHeaderBytes) % 4 == 0)
      << where << ": RVL payload is not a whole number of 32-bit words";
  cv::Mat depth(static_cast<int>(height), static_cast<int>(width), CV_16UC1);
  uint16_t* out = depth.ptr<uint16_t>();
  const int64_t total = int64_t{width} * height;
  NibbleReader reader(data + kHeaderBytes, (size - kHeaderBytes) / 4, where);
  int64_t done = 0;
  int32_t previous = 0;
  while (done < total) {
    const uint32_t zeros = reader.Vle();
    SLAM_THROW_IF_NOT(InputError, zeros <= total - done) << where << ": RVL zero run overflows";
    std::memset(out + done, 0, zeros * sizeof(uint16_t));
    done += zeros;
    const uint32_t nonzeros = reader.Vle();
    SLAM_THROW_IF_NOT(InputError, nonzeros <= total - done)
        << where << ": RVL value run overflows";
    for (uint32_t i = 0; i < nonzeros; ++i) {
      const uint32_t u = reader.Vle();
      const int32_t delta = static_cast<int32_t>(u >> 1) ^ -static_cast<int32_t>(u & 1u);
      previous = static_cast<uint16_t>(previous + delta);
      out[done++] = static_cast<uint16_t>(previous);
    }
  }
  return depth;
}

std::vector<uint8_t> EncodeRvlBlob(const cv::Mat& depth_u16) {
  SLAM_CHECK(depth_u16.type() == CV_16UC1 && depth_u16.isContinuous());
  std::vector<uint8_t> out(kMagic, kMagic + 8);
  out.reserve(kHeaderBytes + 3 * depth_u16.total() + 20);
  WriteLe32(static_cast<uint32_t>(depth_u16.cols), &out);
  WriteLe32(static_cast<uint32_t>(depth_u16.rows), &out);
  NibbleWriter writer(&out);
  const uint16_t* p = depth_u16.ptr<uint16_t>();
  const uint16_t* end = p + depth_u16.total();
  int32_t previous = 0;
  while (p != end) {
    uint32_t zeros = 0;
    while (p != end && *p == 0) ++zeros, ++p;
    writer.Vle(zeros);
    const uint16_t* run = p;
    while (p != end && *p != 0) ++p;
    writer.Vle(static_cast<uint32_t>(p - run));
    for (; run != p; ++run) {
      const int32_t delta = static_cast<int32_t>(*run) - previous;
      writer.Vle((static_cast<uint32_t>(delta) << 1) ^ static_cast<uint32_t>(delta >> 31));
      previous = *run;
    }
  }
  writer.Finish();
  return out;
}

}  // namespace duskmap
