#include "slam/training/training_data_files.h"

#include <system_error>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/json_reader.h"
#include "slam/core/system_error.h"
#include "slam/io/output_safety.h"
#include "slam/training/held_out.h"
#include "slam/training/training_data_files_json.h"

namespace fs = std::filesystem;

namespace duskmap {
namespace {

constexpr const char* kManifestFile = "manifest.json";

void OpenForWriting(const std::string& path, std::ofstream* out) {
  out->open(path, std::ios::binary | std::ios::trunc);
  SLAM_THROW_IF_NOT(InputError, out->good()) << path << ": cannot write: " << LastSystemError();
}

void CheckWritten(const std::ofstream& out, const std::string& path) {
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": write failed: " << LastSystemError();
}

TrainingSceneRecord SceneRecord(const TrainingScene& scene, const ScenePairs& pairs, int64_t first_pair,
                                const TrainingDataOptions& options) {
  TrainingSceneRecord record;
  record.index = scene.index;
  record.seed = scene.config.seed;
  record.texture_seed = SceneTextureSeed(scene.config);
  record.day_of_year = scene.config.lighting.site.day_of_year;
  for (const SessionSpec& session : scene.config.sessions) record.clock_times.push_back(session.clock_time);
  const std::string signature = FurnitureSignature(scene.config.scene.furniture);
  record.furniture_signature_hash = Checksum64Hex(signature.data(), signature.size());
  record.split = scene.index >= options.scenes.scenes - options.validation_scenes ? "validation" : "train";
  record.first_pair = first_pair;
  record.pairs = pairs.pairs;
  return record;
}

int64_t FileBytes(const fs::path& path) {
  std::error_code error;
  SLAM_THROW_IF_NOT(InputError, fs::is_regular_file(path, error))
      << path.string() << ": missing (an incomplete training-data folder)";
  const uintmax_t bytes = fs::file_size(path, error);
  SLAM_THROW_IF_NOT(InputError, !error) << path.string() << ": cannot read its size: " << error.message();
  return static_cast<int64_t>(bytes);
}

TrainingDataFile ExpectedFile(const char* name, const TrainingDataManifest& manifest) {
  const int64_t p = manifest.patch.patch_size_px;
  if (std::string(name) == kTrainingPatchesFile) {
    return {name, "uint8", {manifest.pairs, 2, p, p}, manifest.pairs * 2 * p * p};
  }
  return {name, "float32", {manifest.pairs, 3}, manifest.pairs * 3 * static_cast<int64_t>(sizeof(float))};
}

// The manifest's own consistency: files as the pairs and patch size give
// them, the scenes' pairs contiguous and adding up.
void CheckManifest(const TrainingDataManifest& manifest, const std::string& path) {
  SLAM_THROW_IF_NOT(InputError, ToJsonObject(manifest.patch) == ToJsonObject(manifest.data.patch))
      << path << ": patch differs from data.patch";
  SLAM_THROW_IF_NOT(InputError, manifest.files.size() == 2) << path << ": expected 2 files, got " << manifest.files.size();
  const char* names[] = {kTrainingPatchesFile, kTrainingPointsFile};
  for (size_t i = 0; i < 2; ++i) {
    const TrainingDataFile expected = ExpectedFile(names[i], manifest);
    const TrainingDataFile& file = manifest.files[i];
    SLAM_THROW_IF_NOT(InputError, file.name == expected.name && file.dtype == expected.dtype &&
                                      file.shape == expected.shape && file.bytes == expected.bytes)
        << path << ": files[" << i << "] is not " << expected.name << " of " << expected.bytes
        << " bytes as its " << manifest.pairs << " pairs give";
  }
  int64_t next = 0;
  for (const TrainingSceneRecord& scene : manifest.scenes) {
    SLAM_THROW_IF_NOT(InputError, scene.first_pair == next && scene.pairs >= 0)
        << path << ": scene " << scene.index << " starts at pair " << scene.first_pair << ", expected " << next;
    next += scene.pairs;
  }
  SLAM_THROW_IF_NOT(InputError, next == manifest.pairs && manifest.train_pairs + manifest.validation_pairs == next)
      << path << ": the scenes' pairs (" << next << ") do not add up to pairs " << manifest.pairs;
}

}  // namespace

bool IsTrainingDataFolder(const fs::path& path) {
  std::error_code error;
  if (!fs::is_directory(path, error)) return false;
  try {
    const nlohmann::json json = ReadJsonFile((path / kManifestFile).string());
    return json.is_object() && json.contains("format") && json.at("format") == kTrainingDataFormat;
  } catch (const Error&) {
    return false;
  }
}

OwnedOutput OwnedTrainingData() {
  return {"duskmap training data (no manifest.json of format duskmap-training-pairs)", &IsTrainingDataFolder};
}

TrainingDataWriter::TrainingDataWriter(const std::string& final_path, bool overwrite,
                                       const TrainingDataOptions& options)
    : staged_(final_path, overwrite, OwnedTrainingData()) {
  options.Check();
  manifest_.data = options;
  manifest_.patch = options.patch;
  OpenForWriting(staged_.staging_path() + "/" + kTrainingPatchesFile, &patches_);
  OpenForWriting(staged_.staging_path() + "/" + kTrainingPointsFile, &points_);
}

void TrainingDataWriter::Append(const TrainingScene& scene, const ScenePairs& pairs) {
  CheckHeldOut(scene);
  const int64_t p = manifest_.patch.patch_size_px;
  SLAM_CHECK(scene.index == pairs.scene_index && scene.index == static_cast<int>(manifest_.scenes.size()));
  SLAM_CHECK(static_cast<int64_t>(pairs.patches.size()) == pairs.pairs * 2 * p * p &&
             static_cast<int64_t>(pairs.points_in_world.size()) == pairs.pairs * 3);
  patches_.write(reinterpret_cast<const char*>(pairs.patches.data()), static_cast<std::streamsize>(pairs.patches.size()));
  CheckWritten(patches_, staged_.final_path() + "/" + kTrainingPatchesFile);
  points_.write(reinterpret_cast<const char*>(pairs.points_in_world.data()),
                static_cast<std::streamsize>(pairs.points_in_world.size() * sizeof(float)));
  CheckWritten(points_, staged_.final_path() + "/" + kTrainingPointsFile);
  const TrainingSceneRecord record = SceneRecord(scene, pairs, manifest_.pairs, manifest_.data);
  manifest_.scenes.push_back(record);
  manifest_.pairs += pairs.pairs;
  (record.split == "train" ? manifest_.train_pairs : manifest_.validation_pairs) += pairs.pairs;
}

const TrainingDataManifest& TrainingDataWriter::Finish() {
  patches_.close();
  CheckWritten(patches_, staged_.final_path() + "/" + kTrainingPatchesFile);
  points_.close();
  CheckWritten(points_, staged_.final_path() + "/" + kTrainingPointsFile);
  manifest_.files = {ExpectedFile(kTrainingPatchesFile, manifest_), ExpectedFile(kTrainingPointsFile, manifest_)};
  nlohmann::json json = ToJsonObject(manifest_);
  json["data"].erase("threads");
  json["format"] = kTrainingDataFormat;
  json["version"] = kTrainingDataVersion;
  WriteFileAtomically(staged_.staging_path() + "/" + kManifestFile,
                      [&json](std::ostream& out) { out << json.dump(2) << "\n"; });
  staged_.Commit();
  return manifest_;
}

TrainingDataManifest ReadTrainingDataManifest(const std::string& folder) {
  const fs::path dir(folder);
  const std::string path = (dir / kManifestFile).string();
  std::error_code error;
  SLAM_THROW_IF_NOT(InputError, fs::is_regular_file(path, error))
      << path << ": missing (an incomplete training-data folder: manifest.json is written last)";
  const nlohmann::json json = ReadJsonFile(path);
  SLAM_THROW_IF_NOT(InputError, json.is_object() && json.contains("format") &&
                                    json.at("format") == kTrainingDataFormat)
      << path << ": not a training-data manifest (format is not \"" << kTrainingDataFormat << "\")";
  SLAM_THROW_IF_NOT(InputError, json.contains("version") && json.at("version") == kTrainingDataVersion)
      << path << ": version " << (json.contains("version") ? json.at("version").dump() : "missing")
      << ", this duskmap reads version " << kTrainingDataVersion << " (written by another version)";
  nlohmann::json rest = json;
  rest.erase("format");
  rest.erase("version");
  TrainingDataManifest manifest;
  try {
    manifest = ReadJsonOptions<TrainingDataManifest>(rest, path);
  } catch (const ConfigError& e) {
    SLAM_THROW(InputError) << e.what();
  }
  CheckManifest(manifest, path);
  for (const TrainingDataFile& file : manifest.files) {
    const int64_t bytes = FileBytes(dir / file.name);
    SLAM_THROW_IF_NOT(InputError, bytes == file.bytes)
        << (dir / file.name).string() << ": " << bytes << " bytes, the manifest says " << file.bytes
        << " (an incomplete or damaged training-data folder)";
  }
  return manifest;
}

TrainingData ReadTrainingData(const std::string& folder) {
  TrainingData data;
  data.manifest = ReadTrainingDataManifest(folder);
  data.patches.resize(static_cast<size_t>(data.manifest.files[0].bytes));
  data.points_in_world.resize(static_cast<size_t>(data.manifest.pairs * 3));
  const std::pair<std::string, std::pair<char*, size_t>> files[] = {
      {kTrainingPatchesFile, {reinterpret_cast<char*>(data.patches.data()), data.patches.size()}},
      {kTrainingPointsFile,
       {reinterpret_cast<char*>(data.points_in_world.data()), data.points_in_world.size() * sizeof(float)}}};
  for (const auto& [name, buffer] : files) {
    const std::string path = (fs::path(folder) / name).string();
    std::ifstream in(path, std::ios::binary);
    in.read(buffer.first, static_cast<std::streamsize>(buffer.second));
    SLAM_THROW_IF_NOT(InputError, in.gcount() == static_cast<std::streamsize>(buffer.second))
        << path << ": cannot read " << buffer.second << " bytes";
  }
  return data;
}

}  // namespace duskmap
