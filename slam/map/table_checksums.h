// The map file's table checksums: for every table that carries results, the
// row count and the sum of its rows' 64-bit checksums (SqliteStatement::
// RowChecksum over the values as stored), in the table `checksums`. Written
// by SaveMap inside its transaction, verified by every load as it reads the
// rows (map_store.cc): a flipped bit in any value of those tables is an error
// naming the map and the table.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "slam/map/sqlite_db.h"

namespace duskmap::mapdb {

// The queries that read each table back; the checksums are computed over
// these same rows (columns in this order).
inline constexpr const char* kSelectMeta = "SELECT key, value FROM meta";
inline constexpr const char* kSelectSessions =
    "SELECT id, name, clock_time FROM sessions ORDER BY id";
inline constexpr const char* kSelectNodes =
    "SELECT id, session, frame_index, timestamp_s, map_pose, odom_pose, body_from_camera, "
    "camera, truth_pose, num_features, keypoints, points, descriptors, descriptor_scales, "
    "word_ids, word_counts, vocabulary_features FROM nodes ORDER BY id";
inline constexpr const char* kSelectLinks =
    "SELECT from_id, to_id, type, transform, information FROM links";
inline constexpr const char* kSelectWords = "SELECT id, descriptor FROM words ORDER BY id";

inline constexpr const char* kChecksumsSchema =
    "CREATE TABLE checksums(name TEXT PRIMARY KEY, rows INTEGER NOT NULL, checksum TEXT NOT NULL)";

// A table's checksum: the row count and the sum of the rows' checksums (any
// row order; every row carries its key).
struct TableSum {
  int64_t rows = 0;
  uint64_t sum = 0;
  void Add(const SqliteStatement& row, int columns) {
    ++rows;
    sum += row.RowChecksum(columns);
  }
  std::string Hex() const;
};

// Computes every table's checksum from its rows and inserts them into the
// (existing, empty) checksums table.
void WriteChecksums(SqliteDatabase& db);

// The checksums recorded at save, by table name: (rows, checksum).
using StoredChecksums = std::map<std::string, std::pair<int64_t, std::string>>;
// Throws InputError when the map has no checksums table.
StoredChecksums ReadStoredChecksums(SqliteDatabase& db);

// Throws InputError "<path>: table <table> fails its checksum ..." when `sum`
// differs from the stored one, or none was stored.
void VerifyTable(const StoredChecksums& stored, const char* table, const TableSum& sum,
                 const std::string& path);

}  // namespace duskmap::mapdb
