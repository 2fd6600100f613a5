// The content checksum of a file: what decides whether extracted features
// can be reused (a dataset's images and metadata, an h5 feature file, an
// ONNX model). Checksum64 (checksum.h) of each 1 MiB block, then of the
// blocks' checksums and the file's size: every byte counts, a file of any
// size is read once in constant memory, and at the checksum's ~2 GB/s per
// core the page cache or the disk, not the arithmetic, sets the pace.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace duskmap {

// Throws InputError naming the file and the system's reason when it cannot
// be opened or read, or when it is not a regular file (a FIFO would block).
uint64_t FileChecksum64(const std::filesystem::path& path);
// The same as 16 lowercase hexadecimal digits.
std::string FileChecksum64Hex(const std::filesystem::path& path);
// FileChecksum64 of a file holding these bytes (an embedded model's).
uint64_t BytesChecksum64(const void* data, size_t bytes);

}  // namespace duskmap
