// Feature caches kept across runs (`duskmap run --feature-cache DIR`). An
// extract job whose inputs match an entry restores the entry instead of
// extracting; one that extracts stores its cache there for the next run.
//
// An entry's key is a checksum of everything that shapes a feature cache: the
// entry format, the program (a checksum of the duskmap executable, so a
// rebuilt program never reuses another build's features), the part of the
// dataset's identity the session depends on (datasets/dataset_identity.h:
// the format, the content checksum of the session's files, images and depth
// maps included, and of the files no session owns, such as manifest.json),
// the session, the column's extractor and every feature option, the content
// checksum of a model or h5 file the type reads (experiment/feature_files.h),
// and the frame selection (frame_step, max_frames_per_session). So an image,
// model or h5 file changed in place, even with the same size and time, is
// another key: its session's features are extracted again, the other
// sessions' entries still serve. An entry is a folder <DIR>/<key>/ holding the
// cache file and the extract job's summary. Entries are written whole (a
// partial folder renamed into place) and read whole before use: a damaged or
// half-written entry is a miss, removed and replaced by the extraction.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "slam/experiment/job_results.h"
#include "slam/features/feature_options.h"

namespace duskmap {

// What the cache needs of the run; an empty folder means no cache.
struct SharedFeatureCacheOptions {
  std::filesystem::path folder;
  std::string program_id;           // e.g. a checksum of the executable
  nlohmann::json dataset_identity;  // DatasetIdentity (+ how it was read)
  // {path: checksum} of the model and h5 files, as the run computed them
  // once (RunFeatureFileChecksums); a path not listed is checksummed when a
  // key needs it.
  nlohmann::json file_checksums = nlohmann::json::object();
};

// What one extract job's features depend on.
struct FeatureCacheInputs {
  std::string session;
  std::string cache_name;  // the job's extractor (FeatureSetup::CacheName)
  FeatureOptions features;
  int frame_step = 1;
  int max_frames_per_session = 0;
};

class SharedFeatureCache {
 public:
  explicit SharedFeatureCache(SharedFeatureCacheOptions options);

  bool enabled() const { return !options_.folder.empty(); }
  // The entry's key: 16 hexadecimal digits.
  std::string KeyOf(const FeatureCacheInputs& inputs) const;

  // Links (or copies) the entry `key` to `cache_file` and returns its
  // summary; nullopt when there is no entry or it is damaged (then removed):
  // a summary that is no ExtractJobSummary, or whose frames are not the file's.
  std::optional<ExtractJobSummary> Restore(const std::string& key,
                                           const std::filesystem::path& cache_file) const;
  // Stores `cache_file` and `summary` as entry `key`, replacing an older one.
  // Throws InputError naming the folder when it cannot be written.
  void Store(const std::string& key, const std::filesystem::path& cache_file,
             const ExtractJobSummary& summary) const;

  static constexpr const char* kEntryFile = "features.bin";
  static constexpr const char* kSummaryFile = "summary.json";  // a job's (ReadExtractJobSummary)

 private:
  // {path: checksum} of the files the inputs' feature type reads, and of the
  // model embedded in the program that it runs (EmbeddedModelChecksums).
  nlohmann::json FileChecksumsOf(const FeatureCacheInputs& inputs) const;

  SharedFeatureCacheOptions options_;
};

}  // namespace duskmap
