// Bytes written and read back field by field, for binary records the program
// writes itself (e.g. a vocabulary index stored in a map). Values are copied
// in the machine's byte order; the reader never reads past its end and
// reports a short record instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace duskmap {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<uint8_t>* out) : out_(out) {}

  template <typename T>
  void Put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    PutBytes(&value, sizeof(T));
  }
  // A count (uint64) then the elements.
  template <typename T, typename A>
  void PutVector(const std::vector<T, A>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    Put<uint64_t>(values.size());
    PutBytes(values.data(), values.size() * sizeof(T));
  }
  void PutString(const std::string& text) {
    Put<uint64_t>(text.size());
    PutBytes(text.data(), text.size());
  }
  void PutBytes(const void* data, size_t bytes) {
    const uint8_t* p = static_cast<const uint8_t*>(data);
    out_->insert(out_->end(), p, p + bytes);
  }

 private:
  std::vector<uint8_t>* out_;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  // False (value unchanged) when fewer than sizeof(T) bytes remain.
  template <typename T>
  bool Get(T* value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (size_ - offset_ < sizeof(T)) return false;
    std::memcpy(value, data_ + offset_, sizeof(T));
    offset_ += sizeof(T);
    return true;
  }
  // A count then the elements; false when the count exceeds what remains
  // (checked before anything is allocated) or `max_count`.
  template <typename T, typename A>
  bool GetVector(std::vector<T, A>* values, uint64_t max_count = UINT64_MAX) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t count = 0;
    if (!Get(&count) || count > max_count || count > (size_ - offset_) / sizeof(T)) return false;
    values->resize(count);
    std::memcpy(values->data(), data_ + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
    return true;
  }
  bool GetString(std::string* text) {
    uint64_t count = 0;
    if (!Get(&count) || count > size_ - offset_) return false;
    text->assign(reinterpret_cast<const char*>(data_ + offset_), count);
    offset_ += count;
    return true;
  }
  size_t remaining() const { return size_ - offset_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

}  // namespace duskmap
