#include "slam/experiment/feature_files.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "slam/core/file_checksum.h"
#include "slam/features/feature_registry.h"

namespace duskmap {
namespace fs = std::filesystem;

std::vector<std::string> FeatureFilesOf(const FeatureOptions& features) {
  const FeatureType* type = FindFeatureType(features.type);
  if (type == nullptr || !type->file) return {};
  const std::string& path = FeatureFilePath(features);
  if (path.empty()) return {};
  std::error_code error;
  if (!type->file->folder_per_session || !fs::is_directory(path, error)) return {path};
  std::vector<std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(path, error)) {
    if (entry.is_regular_file(error)) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

nlohmann::json FileChecksums(const std::vector<std::string>& paths) {
  nlohmann::json checksums = nlohmann::json::object();
  for (const std::string& path : paths) {
    std::error_code error;
    checksums[path] = fs::exists(path, error) ? nlohmann::json(FileChecksum64Hex(path)) : nlohmann::json();
  }
  return checksums;
}

nlohmann::json RunFeatureFileChecksums(const ExperimentOptions& experiment,
                                       const EngineOptions& engine,
                                       const std::vector<std::string>& labels) {
  std::vector<std::string> paths;
  for (const std::string& label : labels) {
    const FeatureSetup& setup = experiment.FeatureSetupOf(label);
    FeatureOptions features = engine.features;
    setup.ApplyTo(&features);
    for (const std::string& path : FeatureFilesOf(features)) paths.push_back(path);
    if (setup.matcher == "superglue" && !engine.matcher.superglue.model_path.empty()) {
      paths.push_back(engine.matcher.superglue.model_path);
    }
  }
  std::sort(paths.begin(), paths.end());
  paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
  return FileChecksums(paths);
}

}  // namespace duskmap
