#include "slam/io/synthetic_dataset.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/core/system_error.h"
#include "slam/core/json_codec.h"
#include "slam/core/json_fields.h"
#include "slam/io/path_status.h"
#include "slam/io/synthetic_dataset_json.h"
#include "slam/io/tum_dataset.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

class SyntheticDatasetReader : public DatasetReader {
 public:
  SyntheticDatasetReader(const std::string& path, const TumReadOptions& options)
      : path_(path), options_(options), manifest_(ReadManifest(path)) {
    for (const ManifestSession& session : manifest_.sessions) {
      infos_.push_back(OpenSession(session.name)->info());
    }
  }
  std::string format() const override { return "synthetic"; }
  std::vector<SessionInfo> Sessions() const override { return infos_; }
  std::unique_ptr<SessionReader> OpenSession(const std::string& name) const override {
    for (const ManifestSession& session : manifest_.sessions) {
      if (session.name != name) continue;
      SessionInfo info;
      info.name = session.name;
      info.clock_time = session.clock_time;
      return OpenTumSession(path_ + "/" + session.folder, info, options_);
    }
    throw InputError(path_ + ": no session named '" + name + "'");
  }

 private:
  std::string path_;
  TumReadOptions options_;
  DatasetManifest manifest_;
  std::vector<SessionInfo> infos_;
};

}  // namespace

bool IsFolderInsideDataset(const std::string& folder) {
  const fs::path path(folder);
  if (folder.empty() || path.is_absolute() || path.has_root_name() || path.has_root_directory()) {
    return false;
  }
  for (const fs::path& part : path) {
    if (part == "..") return false;
  }
  return true;
}

void WriteManifest(const std::string& dataset_path, const DatasetManifest& manifest) {
  nlohmann::json json = ToJsonObject(manifest);
  json["format"] = kSyntheticFormat;
  json["version"] = 1;
  const std::string path = dataset_path + "/" + kManifestFileName;
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": cannot write manifest";
  out << json.dump(2) << "\n";
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": write failed: " << LastSystemError();
}

DatasetManifest ReadManifest(const std::string& dataset_path) {
  const std::string path = dataset_path + "/" + kManifestFileName;
  // A symlink loop or a permission problem is named as such, not as "missing".
  const fs::file_status status = PathStatus(path);
  RefuseNonRegularFile(path);  // a FIFO or a folder is not "missing"
  SLAM_THROW_IF_NOT(InputError, status.type() == fs::file_type::regular)
      << path << ": missing (not a duskmap synthetic dataset)";
  DatasetManifest manifest;
  try {
    JsonFields f(ReadJsonFile(path), path);
    std::string format;
    int version = 0;
    f.ReadRequired("format", &format);
    f.ReadRequired("version", &version);
    SLAM_THROW_IF_NOT(InputError, format == kSyntheticFormat && version == 1)
        << path << ": unsupported format '" << format << "' version " << version;
    JsonCodecReader::ReadFields(f, &manifest);
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
  SLAM_THROW_IF_NOT(InputError, !manifest.sessions.empty()) << path << ": 'sessions' must be a non-empty array";
  std::set<std::string> names;
  for (const ManifestSession& session : manifest.sessions) {
    SLAM_THROW_IF_NOT(InputError, IsFolderInsideDataset(session.folder))
        << path << ": session '" << session.name << "' folder '" << session.folder
        << "' must be a relative path inside the dataset (no '..', not absolute)";
    SLAM_THROW_IF_NOT(InputError, names.insert(session.name).second)
        << path << ": duplicate session '" << session.name << "'";
  }
  return manifest;
}

std::unique_ptr<DatasetReader> OpenSyntheticDataset(const std::string& path,
                                                    const TumReadOptions& options) {
  return std::make_unique<SyntheticDatasetReader>(path, options);
}

}  // namespace duskmap
