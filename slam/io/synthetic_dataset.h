// The duskmap synthetic dataset layout: a folder with manifest.json listing
// its sessions, each a TUM-layout subfolder (see tum_writer.h) with
// odometry.txt, calibration.json and session.json (clock time, light states,
// seed).
//
// manifest.json: {"format": "duskmap-synthetic", "version": 1,
//                 "sessions": [{"name": "1", "folder": "1", "clock_time": "16:46",
//                               "role": "mapping"}, ...]}
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/io/dataset_reader.h"
#include "slam/io/synthetic_marker.h"
#include "slam/io/tum_dataset.h"

namespace duskmap {

struct ManifestSession {
  std::string name;        // "1".."6", "A".."F"
  std::string folder;      // relative to the dataset folder
  std::string clock_time;  // local "HH:MM"
  std::string role;        // "mapping" or "localization"
  // The largest camera move between consecutive frames, metres; absent in
  // datasets written before it was recorded.
  std::optional<double> largest_step_m;
};

// A third-party asset the dataset's frames show (a furniture model), with
// its licence, as the licence asks to be credited.
struct ManifestAsset {
  std::string name;     // "Bed"
  std::string source;   // where it was read from: "BlendSwap-CC-0.sh3f#Blend Swap CC-0#bed1"
  std::string creator;
  std::string license;
};

struct DatasetManifest {
  std::vector<ManifestSession> sessions;
  std::vector<ManifestAsset> assets;  // written only when there are any
};

// True when a manifest's session folder stays inside the dataset: relative,
// non-empty, without a ".." component ("1", "sessions/1"; not "../x", "/tmp").
bool IsFolderInsideDataset(const std::string& folder);

void WriteManifest(const std::string& dataset_path, const DatasetManifest& manifest);
// Throws InputError naming manifest.json and the problem.
DatasetManifest ReadManifest(const std::string& dataset_path);

// Opens a synthetic dataset; every listed session folder is validated now.
// The sessions' rgb.txt/depth.txt are read as OpenTumDataset reads them, with
// `options` (strict 1:1 timestamps unless options.allow_unordered).
std::unique_ptr<DatasetReader> OpenSyntheticDataset(const std::string& path,
                                                    const TumReadOptions& options = {});

}  // namespace duskmap
