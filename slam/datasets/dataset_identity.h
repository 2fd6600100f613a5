// What identifies a dataset's content for `duskmap run --resume`: a resumed
// run must read the same data its finished jobs read. The identity is cheap
// (no image is decoded or hashed): the format, each session's name, frame
// count and clock time, and a checksum over the dataset's index and metadata
// files (text, JSON, YAML, CSV: their bytes) and every other file's relative
// path and size. A regenerated synthetic dataset with another config, an
// edited rgb.txt or a re-exported database changes it.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/io/dataset_reader.h"

namespace duskmap {

// Throws InputError naming the path when it cannot be listed.
nlohmann::json DatasetIdentity(const std::string& path, const std::string& format,
                               const std::vector<SessionInfo>& sessions);

}  // namespace duskmap
