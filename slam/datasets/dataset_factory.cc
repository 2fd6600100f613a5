#include "slam/datasets/dataset_factory.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "slam/core/check.h"
#include "slam/datasets/rtabmap_db_reader.h"
#include "slam/datasets/rtabmap_images_reader.h"
#include "slam/datasets/skipping_session_reader.h"
#include "slam/io/path_status.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_dataset.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

fs::file_status StatusOf(const fs::path& path) { return PathStatus(path); }

bool IsRegularFile(const fs::path& path) {
  return StatusOf(path).type() == fs::file_type::regular;
}

// std::filesystem's errors from the readers (a symlink loop met while listing
// a folder, ...) as InputError naming the path and the problem.
[[noreturn]] void ThrowAsInputError(const fs::filesystem_error& e, const std::string& path) {
  throw InputError((e.path1().empty() ? path : e.path1().string()) + ": " + e.code().message());
}

bool IsSqliteFile(const fs::path& path) {
  if (!IsRegularFile(path)) return false;
  if (path.extension() == ".db") return true;
  char header[16] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(header, sizeof(header));
  return in.gcount() == 16 && std::memcmp(header, "SQLite format 3", 16) == 0;
}

bool HasDatabaseFiles(const fs::path& folder) {
  std::error_code error;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    // Only .db entries are examined: a broken entry of another name is no concern here.
    if (it->path().extension() == ".db" && IsRegularFile(it->path())) return true;
  }
  SLAM_THROW_IF_NOT(InputError, !error) << folder.string() << ": " << error.message();
  return false;
}

std::vector<std::string> MatchingFormats(const fs::path& path) {
  if (IsSqliteFile(path)) return {"rtabmap-db"};
  if (StatusOf(path).type() != fs::file_type::directory) return {};
  // duskmap's manifest and TUM's index files are decisive: their sessions
  // hold rgb/ folders too, which alone would also look like an image release.
  if (IsRegularFile(path / kManifestFileName)) return {"synthetic"};
  if (IsRegularFile(path / "rgb.txt") && IsRegularFile(path / "depth.txt")) {
    return {"tum"};
  }
  std::vector<std::string> formats;
  if (!FindImageSessions(path.string()).empty()) formats.push_back("rtabmap-images");
  if (HasDatabaseFiles(path)) formats.push_back("rtabmap-db");
  return formats;
}

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::unique_ptr<DatasetReader> OpenFormat(const std::string& path, const std::string& format,
                                          const DatasetReadOptions& options) {
  if (format == "rtabmap-db") return OpenRtabmapDatabase(path, options);
  if (format == "rtabmap-images") return OpenRtabmapImages(path, options);
  TumReadOptions tum_options;
  tum_options.allow_unordered = options.allow_unordered;
  if (format == "tum") return OpenTumDataset(path, tum_options);
  SLAM_CHECK(format == "synthetic");
  return OpenSyntheticDataset(path, tum_options);
}

}  // namespace

const std::vector<std::string>& DatasetFormats() {
  static const std::vector<std::string> formats = {"synthetic", "tum", "rtabmap-images",
                                                   "rtabmap-db"};
  return formats;
}

std::string DetectDatasetFormat(const std::string& path) {
  SLAM_THROW_IF_NOT(InputError, StatusOf(path).type() != fs::file_type::not_found)
      << path << ": no such file or folder";
  std::vector<std::string> formats;
  try {
    formats = MatchingFormats(path);
  } catch (const fs::filesystem_error& e) {  // from FindImageSessions' folder listing
    ThrowAsInputError(e, path);
  }
  SLAM_THROW_IF_NOT(InputError, !formats.empty())
      << path << ": cannot detect the dataset format (no manifest.json, rgb.txt+depth.txt, "
         "rgb/ or <prefix>_rgb/ folder, or .db file); pass --dataset-format";
  SLAM_THROW_IF_NOT(InputError, formats.size() == 1)
      << path << ": ambiguous dataset format (" << Join(formats)
      << "); pass --dataset-format";
  return formats.front();
}

std::unique_ptr<DatasetReader> OpenDataset(const std::string& path, const std::string& format) {
  return OpenDataset(path, format, DatasetReadOptions());
}

std::unique_ptr<DatasetReader> OpenDataset(const std::string& path, const std::string& format,
                                           const DatasetReadOptions& options) {
  options.Check();
  const auto& formats = DatasetFormats();
  SLAM_THROW_IF_NOT(ConfigError, format == "auto" || std::find(formats.begin(), formats.end(),
                                                               format) != formats.end())
      << "dataset format '" << format << "' is unknown (expected auto, " << Join(formats) << ")";
  const std::string resolved = format == "auto" ? DetectDatasetFormat(path) : format;
  std::unique_ptr<DatasetReader> reader;
  try {
    reader = OpenFormat(path, resolved, options);
  } catch (const fs::filesystem_error& e) {  // a reader's unchecked filesystem call
    ThrowAsInputError(e, path);
  }
  if (!options.skip_bad_frames) return reader;
  return std::make_unique<SkippingDatasetReader>(std::move(reader), options.skip_log);
}

}  // namespace duskmap
