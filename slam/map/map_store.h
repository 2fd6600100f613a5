// The map store: one SQLite file holding a Map (sessions, nodes with poses,
// keypoints, 3D points, descriptors and word ids, links with information
// matrices, the vocabulary's words, the feature type and its parameters, and
// the schema version), and, when the map has one, the vocabulary's NN index
// (table word_index: a format version, the byte count, a 64-bit checksum and
// the bytes). That table is optional: a map without it loads as before; one
// whose table fails its checks loads without the index, the reason in
// MapWords::index_problem, and the vocabulary builds the index again.
//
// Saving is transactional at the file level: the map is written to
// "<path>.saving-<pid>-<n>", flushed to disk (fsync), then published at <path>
// (io/publish.h: renamed over a duskmap map, or, without overwrite, given the
// name only while it is free) and the directory flushed, so a process killed
// during a save leaves the previous file intact (rename is atomic on POSIX
// file systems) and a file that appears at <path> meanwhile is not replaced.
//
// Loading checks, with one-line InputError messages naming the file: that it
// exists and is an SQLite file, that it is not truncated (the header's page
// count against the file size), its integrity (PRAGMA quick_check), the
// schema version, the feature type the caller expects, every row's sizes, and
// the checksum of every table it reads (table checksums: per table the row
// count and the sum of the rows' 64-bit checksums, computed at save over the
// rows as stored; a flipped bit in any value fails its table's check).
#pragma once

#include <functional>
#include <string>

#include "slam/map/map.h"

namespace duskmap {

// 2: compact node features; 3: word counts, n_j, next word id; 4: 12-byte keypoints (no octave);
// 5: words in the vocabulary's stored form (word_storage); 6: table checksums
inline constexpr int kMapSchemaVersion = 6;

struct MapLoadOptions {
  std::string expected_feature_type;  // "" accepts any; otherwise must equal the map's
  bool verify_integrity = true;       // run PRAGMA quick_check (linear in the file size)
  // false: leave the vocabulary's word descriptors out of the Map (its
  // words().ids stay empty, next_word_id is kept); LoadMapWords reads them
  // apart (LoadMapAndWords does both at once), for a localizer that imports
  // them and then lets them go.
  bool load_words = true;
  // LoadMapAndWords only: the node descriptor rows that are a word's stored
  // row become references to the word (map/shared_rows.h), about a third
  // of a binary night map's descriptor bytes. Decode() of those nodes then
  // needs the vocabulary the words go into; the map cannot be saved.
  bool share_node_rows_with_words = true;
  // false: drop the keypoint responses (CompactFeatures::
  // DropKeypointResponses), 4 bytes per feature, for a localizer whose
  // matcher does not read them (all but SuperGlue). The map cannot be saved.
  bool keep_keypoint_responses = true;
};

// True when `path` is a file duskmap's SaveMap wrote (an SQLite file with a
// meta table holding schema_version), of any schema version: what
// `--overwrite` may replace.
bool IsDuskmapMapFile(const std::string& path);

// The steps of a save, in order: the temporary file "<path>.saving-<pid>-<n>"
// is created and its transaction begun, its tables written, the transaction
// committed, the file flushed to disk, published at `path`.
enum class MapSaveStep { kTemporaryCreated, kTablesWritten, kCommitted, kFlushed, kRenamed };

struct MapSaveOptions {
  // Called after each step (tests: a process killed at a chosen step).
  std::function<void(MapSaveStep)> after_step;
  // true: a duskmap map at `path` is replaced (anything else is refused);
  // false: the save fails when any file is at `path` when it is published,
  // one that appeared while the map was built included, and leaves it as it
  // was (`duskmap map` without --overwrite).
  bool overwrite = true;
  std::string flag = "map";  // what named the path, for messages ("--output")
};

// Throws InputError naming the path when the file cannot be written or may
// not be replaced. A save that fails or is killed at any step leaves the
// previous file at `path` (or none) and at most a stale temporary file of a
// killed process, which the next save to `path` removes.
void SaveMap(const Map& map, const std::string& path, const MapSaveOptions& options = {});

Map LoadMap(const std::string& path, const MapLoadOptions& options = MapLoadOptions());

// The vocabulary's words of a stored map, with the same checks as LoadMap
// (options.load_words is ignored).
MapWords LoadMapWords(const std::string& path, const MapLoadOptions& options = MapLoadOptions());

// The map without its words plus the words apart (as load_words = false
// followed by LoadMapWords), from one opening and one integrity check of the
// file: what a localizer that imports the words and lets them go needs. The
// words and the integrity check are read on their own connections beside the
// nodes (LoadMap does the same).
struct MapAndWords {
  Map map;
  MapWords words;
};
MapAndWords LoadMapAndWords(const std::string& path,
                            const MapLoadOptions& options = MapLoadOptions());

}  // namespace duskmap
