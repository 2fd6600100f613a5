// Opens any dataset duskmap can read by format name, or by detecting the
// format from the folder contents:
//   synthetic       folder with manifest.json (duskmap's own generator)
//   tum             TUM RGB-D sequence folder (rgb.txt and depth.txt)
//   rtabmap-images  RTAB-Map image release / rtabmap-export output
//   rtabmap-db      RTAB-Map database file, or folder of .db files
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "slam/datasets/dataset_read_options.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

// The format names accepted by OpenDataset (besides "auto").
const std::vector<std::string>& DatasetFormats();

// The format of the dataset at `path`. Throws InputError naming the path when
// no format matches, or when several do (listing them: pass one explicitly).
std::string DetectDatasetFormat(const std::string& path);

// Opens the dataset; `format` is one of DatasetFormats() or "auto". Throws
// ConfigError for an unknown format name, InputError for unreadable data.
// With options.skip_bad_frames, every session's unusable frames are skipped
// and logged to options.skip_log (for every format); options.allow_unordered
// reads the index files of "tum" and "synthetic" datasets leniently. A path
// that cannot be examined (a symlink loop, no permission) is an InputError
// naming it and the problem.
std::unique_ptr<DatasetReader> OpenDataset(const std::string& path,
                                           const std::string& format = "auto");
std::unique_ptr<DatasetReader> OpenDataset(const std::string& path, const std::string& format,
                                           const DatasetReadOptions& options);

}  // namespace duskmap
