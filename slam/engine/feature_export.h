// Writes a dataset's features in hloc's HDF5 layout (h5_feature_file.h), so
// that duskmap's own types (SURF, BRIEF, DAISY, FREAK, ...) can be used in
// hloc, COLMAP and kornia pipelines, and lists the images an external
// extractor should process, for the round trip back into duskmap through the
// h5 type. Group names are "<session>/<image name>", as the h5 type reads a
// dataset file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "slam/features/feature_options.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

struct FeatureExportOptions {
  std::vector<std::string> sessions;  // in this order; empty = every session of the dataset
  std::string output_path;            // the .h5 to write; empty = none (image list only)
  std::string image_list_path;        // "<group name>\t<absolute image file>" per frame; empty = none
  // false: an output is published only while its name is free (a file that
  // appeared there while the export ran is left as it was and the export
  // fails); true: an earlier export (and any image list) is replaced, tested
  // right before the replace (io/publish.h).
  bool overwrite = false;
  void Check() const;                 // at least one output
};

struct FeatureExportSummary {
  int sessions = 0;
  int64_t frames = 0;
  double mean_features = 0.0;   // per frame
  double mean_extract_ms = 0.0; // per frame, 0 without an .h5 output
  int64_t output_bytes = 0;
};

// Reads every frame of the sessions; with an .h5 output, extracts each with
// `features` and writes its group. Each output is written whole or not at all
// (a partial file is removed). Throws InputError naming the session and frame
// when a frame has no image name (RTAB-Map databases); an unknown session
// gets the reader's InputError. `progress`, when set, is called after each session.
FeatureExportSummary ExportFeatures(
    const DatasetReader& dataset, const FeatureOptions& features, const FeatureExportOptions& options,
    const std::function<void(const std::string& session, int64_t frames)>& progress = nullptr);

// The marker an export leaves in its file (root attribute), and whether a
// path holds a duskmap export (what `--overwrite` may replace).
inline constexpr const char* kFeatureExportAttribute = "duskmap_feature_type";
bool IsDuskmapFeatureExport(const std::string& path);

}  // namespace duskmap
