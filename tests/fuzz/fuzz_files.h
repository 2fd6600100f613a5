// What the fuzz targets that read folders share: an input of the form
// "@@<relative path>\n<bytes>\n@@<path>\n<bytes>..." becomes files under a
// scratch folder, with the paths kept inside it.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <system_error>

namespace duskmap::fuzz {

// A relative path of plain characters, without "..", at most 80 bytes.
inline bool SafePath(const std::string& path) {
  if (path.empty() || path.size() > 80 || path[0] == '/') return false;
  for (char c : path) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' ||
          c == '/')) {
      return false;
    }
  }
  for (const auto& part : std::filesystem::path(path)) {
    if (part == "..") return false;
  }
  return true;
}

inline void WriteBytes(const std::filesystem::path& path, const char* data, size_t size) {
  std::error_code error;
  std::filesystem::create_directories(path.parent_path(), error);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(data, static_cast<std::streamsize>(size));
}

// Calls `section(name, begin, end)` for each "@@<name>" section of `text`,
// [begin, end) being its bytes (without the newline before the next "@@").
inline void ForEachSection(const std::string& text,
                           const std::function<void(const std::string&, size_t, size_t)>& section) {
  size_t at = text.rfind("@@", 0) == 0 ? 0 : text.find("\n@@");
  if (at != std::string::npos && at > 0) ++at;  // at the "@@"
  while (at != std::string::npos) {
    const size_t header_end = text.find('\n', at);
    const std::string name =
        text.substr(at + 2, (header_end == std::string::npos ? text.size() : header_end) - at - 2);
    const size_t begin = header_end == std::string::npos ? text.size() : header_end + 1;
    const size_t next = text.find("\n@@", begin == 0 ? 0 : begin - 1);
    size_t end = next == std::string::npos ? text.size() : std::max(next, begin);
    if (next == std::string::npos && end > begin && text[end - 1] == '\n') --end;
    section(name, begin, end);
    at = next == std::string::npos ? next : next + 1;
  }
}

}  // namespace duskmap::fuzz
