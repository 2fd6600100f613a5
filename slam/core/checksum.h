// A 64-bit checksum of a byte range (FNV-1a over 8-byte words), for records the program stores
// and reads back: it detects truncation and accidental damage, not a
// deliberate forgery.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace duskmap {

uint64_t Checksum64(const void* data, size_t bytes);
// The checksum as 16 lowercase hexadecimal digits.
std::string Checksum64Hex(const void* data, size_t bytes);

}  // namespace duskmap
