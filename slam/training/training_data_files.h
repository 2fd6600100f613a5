// The training-data folder, format "duskmap-training-pairs" version 1
// (docs/learned_descriptor.md):
//   patches.u8    pairs x 2 x P x P bytes: each pair's patch in A, then in B
//   points.f32    pairs x 3 float32 (little-endian), metres: the pair's world point
//   manifest.json written last: format, version, the "data" options it was
//                 made with, the patch sampler's options, each scene (seeds, date, clock times, split,
//                 first pair and count), the totals and both files' sizes.
// The writer stages the folder and publishes it whole (io/folder_commit.h);
// the reader refuses an incomplete folder or another format or version
// with one line naming the file (scripts/train_descriptor.py checks the same).
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "slam/io/folder_commit.h"
#include "slam/io/named_path.h"
#include "slam/synthetic/training_scenes.h"
#include "slam/training/training_data_options.h"
#include "slam/training/training_pairs.h"

namespace duskmap {

inline constexpr const char* kTrainingDataFormat = "duskmap-training-pairs";
inline constexpr int kTrainingDataVersion = 1;
inline constexpr const char* kTrainingPatchesFile = "patches.u8";
inline constexpr const char* kTrainingPointsFile = "points.f32";

struct TrainingSceneRecord {
  int index = 0;
  uint64_t seed = 0;          // its generator seed
  uint64_t texture_seed = 0;  // its apartment's texture seed
  int day_of_year = 0;
  std::vector<std::string> clock_times;  // one session each
  std::string furniture_signature_hash;  // Checksum64Hex of FurnitureSignature
  std::string split;                     // "train" or "validation"
  int64_t first_pair = 0;
  int64_t pairs = 0;
};

struct TrainingDataFile {
  std::string name;              // patches.u8, points.f32
  std::string dtype;             // uint8, float32
  std::vector<int64_t> shape;    // [pairs, 2, P, P], [pairs, 3]
  int64_t bytes = 0;
};

struct TrainingDataManifest {
  TrainingDataOptions data;   // written without "threads" (the output does not depend on it)
  PatchSamplerOptions patch;  // the patches' sampler: data.patch, where readers look first
  std::vector<TrainingSceneRecord> scenes;
  int64_t pairs = 0;
  int64_t train_pairs = 0;
  int64_t validation_pairs = 0;
  std::vector<TrainingDataFile> files;  // patches.u8, then points.f32
};

// A folder whose manifest.json says "format": "duskmap-training-pairs".
bool IsTrainingDataFolder(const std::filesystem::path& path);
OwnedOutput OwnedTrainingData();

class TrainingDataWriter {
 public:
  // Stages `final_path` (StagedFolder: an existing folder is replaced only
  // with `overwrite` and only when it is training data duskmap wrote).
  TrainingDataWriter(const std::string& final_path, bool overwrite, const TrainingDataOptions& options);
  // Appends a scene's pairs, scenes in index order. ConfigError when the
  // scene breaks the held-out rule (held_out.h).
  void Append(const TrainingScene& scene, const ScenePairs& pairs);
  // Writes manifest.json and publishes the folder.
  const TrainingDataManifest& Finish();
  const std::string& final_path() const { return staged_.final_path(); }
  const TrainingDataManifest& manifest() const { return manifest_; }

 private:
  StagedFolder staged_;
  std::ofstream patches_;
  std::ofstream points_;
  TrainingDataManifest manifest_;
};

// Reads and checks `folder`'s manifest.json and that both files are there
// with the sizes it gives. InputError naming the file otherwise.
TrainingDataManifest ReadTrainingDataManifest(const std::string& folder);

struct TrainingData {
  TrainingDataManifest manifest;
  std::vector<uint8_t> patches;
  std::vector<float> points_in_world;
};
TrainingData ReadTrainingData(const std::string& folder);

}  // namespace duskmap
