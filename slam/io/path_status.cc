#include "slam/io/path_status.h"

#include <algorithm>
#include <system_error>

#include "slam/core/check.h"

namespace duskmap {
namespace fs = std::filesystem;

fs::file_status PathStatus(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  SLAM_THROW_IF_NOT(InputError, !error || status.type() == fs::file_type::not_found)
      << path.string() << ": " << error.message();
  return status;
}

bool PathExists(const fs::path& path) {
  return PathStatus(path).type() != fs::file_type::not_found;
}

bool IsDirectoryPath(const fs::path& path) {
  return PathStatus(path).type() == fs::file_type::directory;
}

std::vector<fs::path> SortedFolderEntries(const fs::path& folder) {
  std::error_code error;
  fs::directory_iterator it(folder, error);
  std::vector<fs::path> entries;
  for (; !error && it != fs::directory_iterator(); it.increment(error)) {
    entries.push_back(it->path());
  }
  SLAM_THROW_IF_NOT(InputError, !error) << folder.string() << ": " << error.message();
  std::sort(entries.begin(), entries.end());
  return entries;
}

}  // namespace duskmap
