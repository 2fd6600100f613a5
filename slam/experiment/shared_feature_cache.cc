#include "slam/experiment/shared_feature_cache.h"

#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <system_error>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/system_error.h"
#include "slam/datasets/dataset_identity.h"
#include "slam/experiment/feature_cache.h"
#include "slam/experiment/feature_files.h"
#include "slam/experiment/job_results_json.h"
#include "slam/features/feature_options_json.h"
#include "slam/features/feature_registry.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

// Bumped when the entry layout or the key's meaning changes.
constexpr const char* kEntryFormat = "duskmap-shared-feature-cache-2";

// Reads the whole cache file; its frame count, or nullopt when it is damaged.
std::optional<int64_t> FramesIn(const fs::path& file) {
  try {
    FeatureCacheReader reader(file);
    int64_t frames = 0;
    std::optional<FrameFeatures> features;
    while (reader.Next(&features)) ++frames;
    return frames;
  } catch (const Error&) {
    return std::nullopt;
  }
}

// Copies `from` to the new file `to`; a failed write throws InputError
// "<to>: write failed: <the system's reason>" (std::filesystem::copy_file
// reports a full disk as "Input/output error").
void CopyFileWhole(const fs::path& from, const fs::path& to) {
  errno = 0;
  std::ifstream in(from, std::ios::binary);
  SLAM_THROW_IF_NOT(InputError, in.is_open()) << from.string() << ": cannot read: " << LastSystemError();
  errno = 0;
  std::ofstream out(to, std::ios::binary | std::ios::trunc);
  SLAM_THROW_IF_NOT(InputError, out.is_open()) << to.string() << ": cannot write: " << LastSystemError();
  std::vector<char> buffer(size_t{1} << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    errno = 0;
    out.write(buffer.data(), in.gcount());
    SLAM_THROW_IF_NOT(InputError, out.good()) << to.string() << ": write failed: " << LastSystemError();
  }
  SLAM_THROW_IF_NOT(InputError, in.eof()) << from.string() << ": read failed: " << LastSystemError();
  errno = 0;
  out.close();
  SLAM_THROW_IF_NOT(InputError, !out.fail()) << to.string() << ": write failed: " << LastSystemError();
}

// Hard-links `from` to `to` (a fresh name: `to` is removed first), copying
// when a link cannot be made (another file system).
void LinkOrCopy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove(to, ec);
  fs::create_hard_link(from, to, ec);
  if (ec) CopyFileWhole(from, to);
}

}  // namespace

SharedFeatureCache::SharedFeatureCache(SharedFeatureCacheOptions options)
    : options_(std::move(options)) {
  if (!enabled()) return;
  std::error_code ec;
  fs::create_directories(options_.folder, ec);
  SLAM_THROW_IF_NOT(InputError, !ec && fs::is_directory(options_.folder))
      << options_.folder.string() << ": cannot use as a feature cache folder ("
      << (ec ? ec.message() : "not a folder") << ")";
}

nlohmann::json SharedFeatureCache::FileChecksumsOf(const FeatureCacheInputs& inputs) const {
  std::vector<std::string> paths = FeatureFilesOf(inputs.features);
  const FeatureType* type = FindFeatureType(inputs.features.type);
  std::error_code error;
  if (type != nullptr && type->file && type->file->folder_per_session &&
      fs::is_directory(FeatureFilePath(inputs.features), error)) {
    // A folder holds one "<session>.h5" per session; a session reads its own.
    paths = {(fs::path(FeatureFilePath(inputs.features)) / (inputs.session + ".h5")).string()};
  }
  nlohmann::json checksums = nlohmann::json::object();
  for (const std::string& path : paths) {
    const auto known = options_.file_checksums.find(path);
    checksums[path] = known != options_.file_checksums.end() ? *known : FileChecksums({path})[path];
  }
  checksums.update(EmbeddedModelChecksums(inputs.features));
  return checksums;
}

std::string SharedFeatureCache::KeyOf(const FeatureCacheInputs& inputs) const {
  const nlohmann::json key = {
      {"format", kEntryFormat},
      {"program", options_.program_id},
      {"dataset", SessionIdentity(options_.dataset_identity, inputs.session)},
      {"session", inputs.session},
      {"extractor", inputs.cache_name},
      {"features", ToJsonObject(inputs.features)},
      {"files", FileChecksumsOf(inputs)},
      {"frame_step", inputs.frame_step},
      {"max_frames_per_session", inputs.max_frames_per_session}};
  const std::string text = key.dump();  // keys sorted: one text per content
  return Checksum64Hex(text.data(), text.size());
}

std::optional<ExtractJobSummary> SharedFeatureCache::Restore(const std::string& key,
                                                             const fs::path& cache_file) const {
  if (!enabled()) return std::nullopt;
  const fs::path entry = options_.folder / key;
  std::error_code ec;
  if (!fs::is_directory(entry, ec)) return std::nullopt;
  ExtractJobSummary summary;
  bool usable = false;
  try {  // missing, not JSON, nested too deep, or not an extract job's summary: a miss
    summary = ReadExtractJobSummary(entry);
    const std::optional<int64_t> frames = FramesIn(entry / kEntryFile);
    usable = frames && summary.frames == *frames;
  } catch (const nlohmann::json::exception&) {
    usable = false;
  } catch (const Error&) {
    usable = false;
  }
  if (!usable) {  // damaged or half-copied by hand: extract again
    fs::remove_all(entry, ec);
    return std::nullopt;
  }
  LinkOrCopy(entry / kEntryFile, cache_file);
  return summary;
}

void SharedFeatureCache::Store(const std::string& key, const fs::path& cache_file,
                               const ExtractJobSummary& summary) const {
  if (!enabled()) return;
  const fs::path entry = options_.folder / key;
  std::error_code ec;
  if (fs::is_directory(entry, ec)) return;  // stored meanwhile by another run: the same inputs
  const fs::path partial = options_.folder / (key + ".partial-" + std::to_string(::getpid()));
  try {
    fs::remove_all(partial, ec);
    fs::create_directories(partial);
    LinkOrCopy(cache_file, partial / kEntryFile);
    errno = 0;
    std::ofstream out(partial / kSummaryFile);
    out << ToJsonObject(summary).dump(1) << "\n";
    out.close();
    SLAM_THROW_IF_NOT(InputError, out.good())
        << (partial / kSummaryFile).string() << ": cannot write the feature cache's summary: "
        << LastSystemError();
    fs::rename(partial, entry, ec);  // fails when another run stored it first: keep theirs
    if (ec) fs::remove_all(partial, ec);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(partial, ec);
    SLAM_THROW(InputError) << (e.path1().empty() ? options_.folder : e.path1()).string()
                           << ": cannot store a feature cache (" << e.code().message() << ")";
  } catch (const Error&) {
    fs::remove_all(partial, ec);
    throw;
  }
}

}  // namespace duskmap
