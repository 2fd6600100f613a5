// What identifies a dataset's content for `duskmap run --resume` and the
// feature cache kept across runs: a resumed run must read the same data its
// finished jobs read, and a cached session's features must come from the
// bytes the session holds now.
//
// The identity holds the format, each session's name, frame count and clock
// time, the number and total size of the files, and content checksums of
// every file's bytes (FileChecksum64: images, depth maps, index and metadata
// files alike), once per run:
//   "content": {"sessions": {"<name>": <checksum of the session's files>},
//               "shared": <checksum of the files no single session owns>}
// A session owns the files under its folder: the one the manifest names
// for a synthetic dataset, else the top-level folder or file named after the
// session (or, with the extension dropped, a database "<name>.db"); a
// dataset of one session owns every file. The rest (a synthetic dataset's
// manifest.json, a database holding several sessions) is shared: a change
// there changes every session's identity. So an image rewritten in place
// with the same size changes exactly its session's checksum, and every file
// is covered by some checksum.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/io/dataset_reader.h"

namespace duskmap {

// Reads every file of the dataset once. Throws InputError naming the path
// when it cannot be listed, or a file when it cannot be read.
nlohmann::json DatasetIdentity(const std::string& path, const std::string& format,
                               const std::vector<SessionInfo>& sessions);

// The part of a dataset identity that one session's data depend on: the
// identity without the other sessions' listing and content checksums (the
// shared checksum kept), so that a key built on it changes when this
// session's files or the shared ones change, and only then.
nlohmann::json SessionIdentity(const nlohmann::json& dataset_identity, const std::string& session);

}  // namespace duskmap
