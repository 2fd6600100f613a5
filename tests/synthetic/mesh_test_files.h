// Test fixtures for the furniture loaders: in-memory mesh files, small ZIP
// archives written with libzip, encoded images and scratch paths.
#pragma once

#include <unistd.h>
#include <zip.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/synthetic/assets/mesh_files.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {

using FileMap = std::map<std::string, std::string>;

// MeshFiles over `files` (which must outlive it), named "memory" in messages.
inline MeshFiles MemoryFiles(const FileMap& files) {
  MeshFiles mesh_files;
  mesh_files.container = "memory";
  mesh_files.read = [&files](const std::string& path) -> std::optional<std::string> {
    const auto it = files.find(path);
    if (it == files.end()) return std::nullopt;
    return it->second;
  };
  return mesh_files;
}

inline std::string EncodeImage(const cv::Mat& image, const std::string& extension) {
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes));
  return std::string(bytes.begin(), bytes.end());
}

// The first 33 bytes of a PNG (signature and IHDR) declaring width x height:
// enough for the header check, not an image.
inline std::string PngHeader(uint32_t width, uint32_t height) {
  std::string bytes = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
  for (const uint32_t v : {width, height}) {
    for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((v >> shift) & 0xFF);
  }
  bytes += std::string("\x08\x02\x00\x00\x00\x00\x00\x00\x00", 9);
  return bytes;
}

// A scratch folder under the process's temporary root, removed at destruction.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name) : path_(testing::ProcessTempDir(name)) {}
  ~ScratchFolder() { std::filesystem::remove_all(path_); }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// Writes a ZIP archive holding `files` (entry name -> bytes, in order),
// stored uncompressed when `store` is set (so a test can find and damage
// the bytes of an entry).
inline void WriteZip(const std::string& path, const std::vector<std::pair<std::string, std::string>>& files,
                     bool store = false) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  ASSERT_NE(archive, nullptr) << path << ": libzip error " << error;
  for (const auto& [name, bytes] : files) {
    zip_source_t* source = zip_source_buffer(archive, bytes.data(), bytes.size(), 0);
    ASSERT_NE(source, nullptr);
    const zip_int64_t index = zip_file_add(archive, name.c_str(), source, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    ASSERT_GE(index, 0) << name << ": " << zip_strerror(archive);
    if (store) {
      ASSERT_EQ(zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0), 0);
    }
  }
  ASSERT_EQ(zip_close(archive), 0) << path;
}

inline std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Runs `call` and returns the message of the InputError it throws ("" and a
// test failure when it throws none, or a message of more than one line).
template <typename Call>
std::string InputErrorOf(Call&& call) {
  try {
    call();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

}  // namespace duskmap
