#include "slam/engine/feature_export.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/features/feature_factory.h"
#include "slam/features/h5_feature_file.h"
#include "slam/io/publish.h"

namespace duskmap {
namespace fs = std::filesystem;

void FeatureExportOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !output_path.empty() || !image_list_path.empty())
      << "features export: nothing to write (give --output, --image-list or both)";
}

bool IsDuskmapFeatureExport(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return false;
  try {
    const H5FeatureFile file(path, H5FeatureFile::Mode::kRead);
    return file.ReadAttribute(kFeatureExportAttribute).has_value();
  } catch (const InputError&) {
    return false;
  }
}

FeatureExportSummary ExportFeatures(
    const DatasetReader& dataset, const FeatureOptions& features, const FeatureExportOptions& options,
    const std::function<void(const std::string& session, int64_t frames)>& progress) {
  options.Check();
  features.Check();
  std::vector<std::string> sessions = options.sessions;
  if (sessions.empty()) {
    for (const SessionInfo& info : dataset.Sessions()) sessions.push_back(info.name);
  }
  const bool write_h5 = !options.output_path.empty();
  const std::unique_ptr<FeatureExtractor> extractor =
      write_h5 ? CreateFeatureExtractor(features) : nullptr;
  FeatureExportSummary summary;
  std::ostringstream list;
  double features_sum = 0.0;
  double extract_ms_sum = 0.0;
  // Every frame of the sessions into the image list and, when given, `file`.
  auto export_sessions = [&](H5FeatureFile* file) {
    for (const std::string& session : sessions) {
      const std::unique_ptr<SessionReader> reader = dataset.OpenSession(session);
      int64_t frames = 0;
      while (std::optional<RgbdFrame> frame = reader->Next()) {
        SLAM_THROW_IF_NOT(InputError, !frame->image_name.empty())
            << "features export: session '" << session << "' frame " << frame->frame_index
            << " has no image file (RTAB-Map databases hold images as blobs; export the image release)";
        const std::string group = session + "/" + frame->image_name;
        list << group << '\t' << fs::absolute(frame->image_file).lexically_normal().string() << '\n';
        if (file != nullptr) {
          Stopwatch watch;
          const FrameFeatures f = extractor->ExtractFrame(*frame);
          extract_ms_sum += watch.ElapsedMs();
          features_sum += static_cast<double>(f.size());
          file->Write(group, f.keypoints, f.descriptors, f.kind);
        }
        ++frames;
      }
      summary.frames += frames;
      ++summary.sessions;
      if (progress) progress(session, frames);
    }
  };
  if (write_h5) {
    // Written beside the output and published once complete.
    const PublishTarget target{{"--output", options.output_path},
                               options.overwrite,
                               {"a duskmap feature export", [](const fs::path& p) {
                                  return IsDuskmapFeatureExport(p.string());
                                }}};
    WriteAndPublishAt(target, [&](const std::string& partial) {
      H5FeatureFile file(partial, H5FeatureFile::Mode::kCreate);
      file.WriteAttribute(kFeatureExportAttribute, features.type);
      export_sessions(&file);
      file.Close();
    });
    summary.output_bytes = static_cast<int64_t>(fs::file_size(options.output_path));
  } else {
    export_sessions(nullptr);
  }
  if (!options.image_list_path.empty()) {
    const PublishTarget target{{"--image-list", options.image_list_path},
                               options.overwrite,
                               {"a file (image lists are plain text)", [](const fs::path& p) {
                                  return fs::is_regular_file(p);
                                }}};
    WriteAndPublish(target, [&](std::ostream& out) { out << list.str(); });
  }
  if (summary.frames > 0 && write_h5) {
    summary.mean_features = features_sum / static_cast<double>(summary.frames);
    summary.mean_extract_ms = extract_ms_sum / static_cast<double>(summary.frames);
  }
  return summary;
}

}  // namespace duskmap
