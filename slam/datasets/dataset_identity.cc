#include "slam/datasets/dataset_identity.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "slam/core/check.h"
#include "slam/core/checksum.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

constexpr uintmax_t kMaxHashedFileBytes = 16u << 20;  // index files are far smaller

bool IsMetadataFile(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".txt" || ext == ".json" || ext == ".yaml" || ext == ".yml" || ext == ".csv";
}

uint64_t Mix(uint64_t h, uint64_t value) { return (h ^ value) * 0x100000001b3ull ^ (h >> 29); }

uint64_t MixText(uint64_t h, const std::string& text) {
  return Mix(h, Checksum64(text.data(), text.size()));
}

}  // namespace

nlohmann::json DatasetIdentity(const std::string& path, const std::string& format,
                               const std::vector<SessionInfo>& sessions) {
  nlohmann::json identity;
  identity["format"] = format;
  nlohmann::json listed = nlohmann::json::array();
  for (const SessionInfo& s : sessions) {
    listed.push_back({{"name", s.name},
                      {"frames", s.num_frames},
                      {"clock_time", s.clock_time ? *s.clock_time : std::string()}});
  }
  identity["sessions"] = listed;

  // Files in a fixed order (sorted relative paths), so that the checksum
  // does not depend on the directory's listing order.
  std::error_code error;
  std::vector<std::pair<std::string, fs::path>> files;
  if (fs::is_directory(path, error)) {
    fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, error);
    SLAM_THROW_IF_NOT(InputError, !error) << path << ": cannot list the dataset (" << error.message() << ")";
    for (; it != fs::recursive_directory_iterator(); it.increment(error)) {
      SLAM_THROW_IF_NOT(InputError, !error)
          << path << ": cannot list the dataset (" << error.message() << ")";
      if (it->is_regular_file(error)) {
        files.push_back({fs::relative(it->path(), path, error).generic_string(), it->path()});
      }
    }
  } else {
    files.push_back({fs::path(path).filename().string(), fs::path(path)});
  }
  std::sort(files.begin(), files.end());
  uint64_t h = 0xcbf29ce484222325ull;
  uintmax_t total_bytes = 0;
  for (const auto& [relative, full] : files) {
    const uintmax_t bytes = fs::file_size(full, error);
    SLAM_THROW_IF_NOT(InputError, !error) << full.string() << ": cannot stat (" << error.message() << ")";
    total_bytes += bytes;
    h = MixText(h, relative);
    h = Mix(h, bytes);
    if (IsMetadataFile(full) && bytes <= kMaxHashedFileBytes) {
      std::ifstream in(full, std::ios::binary);
      const std::string content((std::istreambuf_iterator<char>(in)), {});
      SLAM_THROW_IF_NOT(InputError, in.good() || in.eof()) << full.string() << ": cannot read";
      h = MixText(h, content);
    }
  }
  identity["files"] = files.size();
  identity["bytes"] = total_bytes;
  identity["checksum"] = Checksum64Hex(&h, sizeof(h));
  return identity;
}

}  // namespace duskmap
