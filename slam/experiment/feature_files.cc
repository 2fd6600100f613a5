#include "slam/experiment/feature_files.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "slam/core/file_checksum.h"
#include "slam/features/embedded_model.h"
#include "slam/features/feature_registry.h"

namespace duskmap {
namespace fs = std::filesystem;

std::vector<std::string> FeatureFilesOf(const FeatureOptions& features) {
  const FeatureType* type = FindFeatureType(features.type);
  if (type == nullptr) return {};
  const std::string& path = FeatureFilePath(features);
  if (path.empty()) return {};
  std::error_code error;
  if (!type->file || !type->file->folder_per_session || !fs::is_directory(path, error)) return {path};
  std::vector<std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(path, error)) {
    if (entry.is_regular_file(error)) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

nlohmann::json EmbeddedModelChecksums(const FeatureOptions& features) {
  nlohmann::json checksums = nlohmann::json::object();
  if (features.type == FeatureTypeName(FeatureTypeId::kDuskNet) && features.dusknet.model_path.empty()) {
    const EmbeddedModel& model = EmbeddedDuskNetModel();
    checksums[model.name] = model.checksum_hex;
  }
  return checksums;
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
  nlohmann::json embedded = nlohmann::json::object();
  for (const std::string& label : labels) {
    const FeatureSetup& setup = experiment.FeatureSetupOf(label);
    FeatureOptions features = engine.features;
    setup.ApplyTo(&features);
    for (const std::string& path : FeatureFilesOf(features)) paths.push_back(path);
    embedded.update(EmbeddedModelChecksums(features));
    if (setup.matcher == "superglue" && !engine.matcher.superglue.model_path.empty()) {
      paths.push_back(engine.matcher.superglue.model_path);
    }
  }
  std::sort(paths.begin(), paths.end());
  paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
  nlohmann::json checksums = FileChecksums(paths);
  checksums.update(embedded);
  return checksums;
}

}  // namespace duskmap
