// Read-only access to the files of a ZIP archive (libzip), by their archive
// paths (archive_path.h). Reads are serialised by a lock: one archive may be
// read from several threads.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace duskmap {

class ZipArchive {
 public:
  // Opens `path` with libzip's consistency checks; throws InputError
  // "<path>: <problem>" when the file is missing, unreadable, not a ZIP
  // archive or corrupt (inconsistent directory).
  static ZipArchive Open(const std::string& path);

  ZipArchive(ZipArchive&&) noexcept;
  ZipArchive& operator=(ZipArchive&&) noexcept;
  ~ZipArchive();

  const std::string& path() const;
  // The archive paths of its files, in archive order; folders and entries
  // whose names are not archive paths (absolute, "..") are left out.
  std::vector<std::string> FilePaths() const;
  // Whether `archive_path` (normalized as archive_path.h says) is a file of
  // the archive; false for any path outside the archive.
  bool Contains(const std::string& archive_path) const;
  // The bytes of a file. Throws InputError "<archive>!/<file>: <problem>"
  // when the path leaves the archive (absolute, ".."), names no file, is
  // larger than `max_bytes` uncompressed, or its data fail to decompress or
  // to match their checksum.
  std::string Read(const std::string& archive_path, int64_t max_bytes) const;

 private:
  struct Impl;
  explicit ZipArchive(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace duskmap
