#include "slam/map/map_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <optional>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/input_file.h"
#include "slam/io/publish.h"
#include "slam/map/map_codec.h"
#include "slam/map/shared_rows.h"
#include "slam/map/table_checksums.h"
#include "slam/map/sqlite_db.h"

namespace duskmap {
namespace {

using mapdb::SqliteDatabase;
using mapdb::SqliteStatement;
using mapdb::StoredChecksums;
using mapdb::TableSum;
using mapdb::VerifyTable;
using mapdb::ReadStoredChecksums;
using mapdb::WriteChecksums;
using mapdb::kSelectMeta;
using mapdb::kSelectSessions;
using mapdb::kSelectNodes;
using mapdb::kSelectLinks;
using mapdb::kSelectWords;

constexpr const char* kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE sessions(id INTEGER PRIMARY KEY, name TEXT NOT NULL, clock_time TEXT);
CREATE TABLE nodes(id INTEGER PRIMARY KEY, session INTEGER NOT NULL, frame_index INTEGER NOT NULL,
  timestamp_s REAL NOT NULL, map_pose BLOB NOT NULL, odom_pose BLOB NOT NULL,
  body_from_camera BLOB NOT NULL, camera BLOB NOT NULL, truth_pose BLOB,
  num_features INTEGER NOT NULL, keypoints BLOB NOT NULL, points BLOB NOT NULL,
  descriptors BLOB NOT NULL, descriptor_scales BLOB NOT NULL, word_ids BLOB NOT NULL,
  word_counts BLOB NOT NULL, vocabulary_features INTEGER NOT NULL);
CREATE TABLE links(from_id INTEGER NOT NULL, to_id INTEGER NOT NULL, type INTEGER NOT NULL,
  transform BLOB NOT NULL, information BLOB NOT NULL, PRIMARY KEY(from_id, to_id));
CREATE TABLE words(id INTEGER PRIMARY KEY, descriptor BLOB NOT NULL);
)sql";



// ---- saving -------------------------------------------------------------

void WriteMeta(SqliteDatabase& db, const Map& map) {
  const MapMetadata& m = map.metadata();
  const std::map<std::string, std::string> meta = {
      {"schema_version", std::to_string(kMapSchemaVersion)},
      {"feature_type", m.feature_type},
      {"feature_parameters", m.feature_parameters_json},
      {"engine_parameters", m.engine_parameters_json},
      {"descriptor_kind", m.descriptor_kind == DescriptorKind::kBinary ? "binary" : "float"},
      {"descriptor_cv_type", std::to_string(m.descriptor_cv_type)},
      {"descriptor_cols", std::to_string(m.descriptor_cols)},
      {"descriptor_storage", DescriptorStorageName(m.descriptor_storage)},
      {"word_storage", DescriptorStorageName(m.word_storage)},
      {"last_node_id", std::to_string(map.last_node_id())},
      {"num_sessions", std::to_string(map.sessions().size())},
      {"num_nodes", std::to_string(map.nodes().size())},
      {"num_links", std::to_string(map.links().size())},
      {"num_words", std::to_string(map.words().ids.size())},
      {"next_word_id", std::to_string(map.words().next_word_id)}};
  SqliteStatement insert = db.Prepare("INSERT INTO meta VALUES(?, ?)");
  for (const auto& [key, value] : meta) {
    insert.BindText(1, key);
    insert.BindText(2, value);
    insert.Run();
  }
}

void WriteSessions(SqliteDatabase& db, const Map& map) {
  SqliteStatement insert = db.Prepare("INSERT INTO sessions VALUES(?, ?, ?)");
  for (const MapSession& s : map.sessions()) {
    insert.BindInt(1, s.id);
    insert.BindText(2, s.name);
    if (s.clock_time) {
      insert.BindText(3, *s.clock_time);
    } else {
      insert.BindNull(3);
    }
    insert.Run();
  }
}

void WriteNodes(SqliteDatabase& db, const Map& map) {
  SqliteStatement insert =
      db.Prepare("INSERT INTO nodes VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const auto& [id, n] : map.nodes()) {
    insert.BindInt(1, id);
    insert.BindInt(2, n.session);
    insert.BindInt(3, n.frame_index);
    insert.BindDouble(4, n.timestamp_s);
    insert.BindBlob(5, EncodePose(n.map_from_body));
    insert.BindBlob(6, EncodePose(n.odom_from_body));
    insert.BindBlob(7, EncodePose(n.body_from_camera));
    insert.BindBlob(8, EncodeCamera(n.camera));
    if (n.truth_from_camera) {
      insert.BindBlob(9, EncodePose(*n.truth_from_camera));
    } else {
      insert.BindNull(9);
    }
    insert.BindInt(10, static_cast<int64_t>(n.features.size()));
    insert.BindBlob(11, EncodePackedKeypoints(n.features.keypoints(), n.features.responses()));
    insert.BindBlob(12, EncodeHalfs(n.features.half_points()));
    insert.BindBlob(13, EncodeMatrix(n.features.codes()));
    std::vector<float> scales = n.features.row_offsets();
    scales.insert(scales.end(), n.features.row_steps().begin(), n.features.row_steps().end());
    insert.BindBlob(14, EncodeFloats(scales));
    insert.BindBlob(15, EncodeWordIds(n.word_ids));
    insert.BindBlob(16, EncodeInt32s(n.word_counts));
    insert.BindInt(17, n.vocabulary_features);
    insert.Run();
  }
}

void WriteLinksAndWords(SqliteDatabase& db, const Map& map) {
  SqliteStatement link = db.Prepare("INSERT INTO links VALUES(?, ?, ?, ?, ?)");
  for (const auto& [key, l] : map.links()) {
    link.BindInt(1, l.from);
    link.BindInt(2, l.to);
    link.BindInt(3, static_cast<int>(l.type));
    link.BindBlob(4, EncodePose(l.from_from_to));
    link.BindBlob(5, EncodeInformation(l.information));
    link.Run();
  }
  SqliteStatement word = db.Prepare("INSERT INTO words VALUES(?, ?)");
  const MapWords& words = map.words();
  for (size_t i = 0; i < words.ids.size(); ++i) {
    word.BindInt(1, words.ids[i]);
    word.BindBlob(2, EncodeMatrix(words.descriptors.row(static_cast<int>(i))));
    word.Run();
  }
}

// The vocabulary's NN index (MapWords::index_state), when the map has one:
// an optional table, so that a map without it (older, or saved without an
// index) still loads and rebuilds the index.
constexpr int kWordIndexVersion = 1;

void WriteWordIndex(SqliteDatabase& db, const Map& map) {
  const std::vector<uint8_t>& state = map.words().index_state;
  if (state.empty()) return;
  db.Execute(
      "CREATE TABLE word_index(version INTEGER NOT NULL, bytes INTEGER NOT NULL, "
      "checksum TEXT NOT NULL, state BLOB NOT NULL)");
  SqliteStatement insert = db.Prepare("INSERT INTO word_index VALUES(?, ?, ?, ?)");
  insert.BindInt(1, kWordIndexVersion);
  insert.BindInt(2, static_cast<int64_t>(state.size()));
  insert.BindText(3, Checksum64Hex(state.data(), state.size()));
  insert.BindBlob(4, state);
  insert.Run();
}

void FsyncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  SLAM_THROW_IF_NOT(InputError, fd >= 0) << path << ": cannot open to flush: " << std::strerror(errno);
  const int rc = ::fsync(fd);
  ::close(fd);
  SLAM_THROW_IF_NOT(InputError, rc == 0) << path << ": fsync failed: " << std::strerror(errno);
}

std::string DirectoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// ---- loading ------------------------------------------------------------

uint64_t ReadBigEndian(const unsigned char* bytes, int count) {
  uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

int64_t FileBytes(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 ? static_cast<int64_t>(info.st_size) : 0;
}

// Checks the SQLite header: magic string, and a file at least as long as the
// page count the header declares (a truncated copy fails here).
void CheckFileHeader(const std::string& path) {
  struct stat info;
  SLAM_THROW_IF_NOT(InputError, ::stat(path.c_str(), &info) == 0)
      << path << ": no such map file";
  RefuseNonRegularFile(path);  // before opening: a FIFO would block, a folder reads as nothing
  std::ifstream file(path, std::ios::binary);
  unsigned char header[100] = {};
  file.read(reinterpret_cast<char*>(header), sizeof(header));
  SLAM_THROW_IF_NOT(InputError, file.gcount() == sizeof(header) &&
                                    std::memcmp(header, "SQLite format 3", 16) == 0)
      << path << ": not a duskmap map (not an SQLite database, or truncated to "
      << info.st_size << " bytes)";
  uint64_t page_size = ReadBigEndian(header + 16, 2);
  if (page_size == 1) page_size = 65536;
  const uint64_t page_count = ReadBigEndian(header + 28, 4);
  const uint64_t expected = page_size * page_count;
  SLAM_THROW_IF_NOT(InputError, static_cast<uint64_t>(info.st_size) >= expected)
      << path << ": truncated map file (" << info.st_size << " of " << expected << " bytes)";
}

void CheckIntegrity(SqliteDatabase& db) {
  SqliteStatement check = db.Prepare("PRAGMA quick_check");
  SLAM_THROW_IF_NOT(InputError, check.Step()) << db.path() << ": integrity check gave no result";
  std::string result = check.Text(0);
  // SQLite lists its findings on several lines: the error stays one line.
  std::replace(result.begin(), result.end(), '\n', ' ');
  SLAM_THROW_IF_NOT(InputError, result == "ok")
      << db.path() << ": corrupted map file (" << result << ")";
}

std::map<std::string, std::string> ReadMeta(SqliteDatabase& db, TableSum* sum) {
  std::map<std::string, std::string> meta;
  SqliteStatement has = db.Prepare("SELECT count(*) FROM sqlite_master WHERE name = 'meta'");
  SLAM_THROW_IF_NOT(InputError, has.Step() && has.Int(0) == 1)
      << db.path() << ": not a duskmap map (no meta table)";
  SqliteStatement select = db.Prepare(kSelectMeta);
  while (select.Step()) {
    sum->Add(select, 2);
    meta[select.Text(0)] = select.Text(1);
  }
  return meta;
}

const std::string& MetaValue(const std::map<std::string, std::string>& meta,
                             const std::string& key, const std::string& path) {
  auto it = meta.find(key);
  SLAM_THROW_IF_NOT(InputError, it != meta.end()) << path << ": map has no '" << key << "' entry";
  return it->second;
}

int64_t MetaInt(const std::map<std::string, std::string>& meta, const std::string& key,
                const std::string& path) {
  const std::string& text = MetaValue(meta, key, path);
  int64_t value = 0;
  size_t used = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  SLAM_THROW_IF_NOT(InputError, used > 0 && used == text.size())
      << path << ": map entry '" << key << "' is not an integer: '" << text << "'";
  return value;
}

// A DescriptorStorage entry of the meta table; `what` names it in the error.
DescriptorStorage MetaStorage(const std::map<std::string, std::string>& meta, const std::string& key,
                              const char* what, const std::string& path) {
  const std::string& name = MetaValue(meta, key, path);
  const std::optional<DescriptorStorage> storage = DescriptorStorageFromName(name);
  SLAM_THROW_IF_NOT(InputError, storage.has_value())
      << path << ": unknown " << what << " '" << name << "'";
  return *storage;
}

MapMetadata ReadMetadata(const std::map<std::string, std::string>& meta, const std::string& path,
                         const MapLoadOptions& options) {
  const int64_t version = MetaInt(meta, "schema_version", path);
  SLAM_THROW_IF_NOT(InputError, version == kMapSchemaVersion)
      << path << ": map schema version " << version << " is not supported (this build reads "
      << kMapSchemaVersion
      << (version < kMapSchemaVersion ? "; the map was written by an older duskmap, rebuild it"
                                      : "")
      << ")";
  MapMetadata m;
  m.feature_type = MetaValue(meta, "feature_type", path);
  SLAM_THROW_IF_NOT(InputError, options.expected_feature_type.empty() ||
                                    options.expected_feature_type == m.feature_type)
      << path << ": map was built with feature type '" << m.feature_type << "', expected '"
      << options.expected_feature_type << "'";
  m.feature_parameters_json = MetaValue(meta, "feature_parameters", path);
  m.engine_parameters_json = MetaValue(meta, "engine_parameters", path);
  m.descriptor_kind = MetaValue(meta, "descriptor_kind", path) == "binary"
                          ? DescriptorKind::kBinary
                          : DescriptorKind::kFloat;
  m.descriptor_cv_type = static_cast<int>(MetaInt(meta, "descriptor_cv_type", path));
  m.descriptor_cols = static_cast<int>(MetaInt(meta, "descriptor_cols", path));
  m.descriptor_storage = MetaStorage(meta, "descriptor_storage", "descriptor storage", path);
  m.word_storage = MetaStorage(meta, "word_storage", "word storage", path);
  return m;
}

void ReadSessions(SqliteDatabase& db, const StoredChecksums& stored, Map* map) {
  SqliteStatement select = db.Prepare(kSelectSessions);
  TableSum sum;
  while (select.Step()) {
    sum.Add(select, 3);
    const SessionId id = map->AddSession(
        select.Text(1),
        select.IsNull(2) ? std::nullopt : std::optional<std::string>(select.Text(2)));
    SLAM_THROW_IF_NOT(InputError, id == select.Int(0))
        << db.path() << ": session ids are not 0, 1, 2, ... (found " << select.Int(0) << ")";
  }
  VerifyTable(stored, "sessions", sum, db.path());
}

MapNode ReadNodeRow(const SqliteStatement& row, const MapMetadata& m, const std::string& path,
                    const MapLoadOptions& options) {
  MapNode n;
  n.id = row.Int(0);
  const std::string what = path + ": node " + std::to_string(n.id);
  n.session = static_cast<SessionId>(row.Int(1));
  n.frame_index = row.Int(2);
  n.timestamp_s = row.Double(3);
  n.map_from_body = DecodePose(row.Blob(4), what + " map pose");
  n.odom_from_body = DecodePose(row.Blob(5), what + " odometry pose");
  n.body_from_camera = DecodePose(row.Blob(6), what + " camera extrinsics");
  n.camera = DecodeCamera(row.Blob(7), what + " camera");
  if (!row.IsNull(8)) n.truth_from_camera = DecodePose(row.Blob(8), what + " ground truth");
  const int64_t count = row.Int(9);
  std::vector<float> responses;
  std::vector<PackedKeypoint> keypoints =
      DecodePackedKeypoints(row.Blob(10), what + " keypoints", &responses);
  std::vector<uint16_t> points = DecodeHalfs(row.Blob(11), what + " 3D points");
  SLAM_THROW_IF_NOT(InputError, static_cast<int64_t>(keypoints.size()) == count &&
                                    static_cast<int64_t>(points.size()) == 3 * count)
      << what << ": keypoint, 3D point and feature counts differ";
  const bool quantized = m.descriptor_kind == DescriptorKind::kFloat &&
                         m.descriptor_storage == DescriptorStorage::kUint8;
  const int code_type = quantized ? CV_8U : m.descriptor_cv_type;
  cv::Mat codes = DecodeMatrix(row.Blob(12), static_cast<int>(count), m.descriptor_cols, code_type,
                               what + " descriptors");
  std::vector<float> scales = DecodeFloats(row.Blob(13), what + " descriptor scales");
  const size_t expected_scales = quantized ? 2 * static_cast<size_t>(count) : 0;
  SLAM_THROW_IF_NOT(InputError, scales.size() == expected_scales)
      << what << ": " << scales.size() << " descriptor scales, expected " << expected_scales;
  std::vector<float> offsets(scales.begin(), scales.begin() + expected_scales / 2);
  std::vector<float> steps(scales.begin() + expected_scales / 2, scales.end());
  n.features = CompactFeatures::FromParts(m.descriptor_kind, m.descriptor_storage,
                                          m.descriptor_cv_type, std::move(codes),
                                          std::move(offsets), std::move(steps),
                                          std::move(keypoints), std::move(responses),
                                          std::move(points));
  if (!options.keep_keypoint_responses) n.features.DropKeypointResponses();
  n.word_ids = DecodeWordIds(row.Blob(14), what + " word ids");
  n.word_counts = DecodeInt32s(row.Blob(15), what + " word counts");
  SLAM_THROW_IF_NOT(InputError, n.word_counts.size() == n.word_ids.size())
      << what << ": " << n.word_counts.size() << " word counts for " << n.word_ids.size()
      << " words";
  const int64_t vocabulary_features = row.Int(16);
  SLAM_THROW_IF_NOT(InputError, vocabulary_features >= 0 && vocabulary_features <= count)
      << what << ": " << vocabulary_features << " vocabulary features of " << count;
  n.vocabulary_features = static_cast<int32_t>(vocabulary_features);
  // Each word occurs at least once among the quantized features, and no more
  // often than they are (an importer expands the counts).
  int64_t occurrences = 0;
  for (const int32_t c : n.word_counts) {
    SLAM_THROW_IF_NOT(InputError, c >= 1) << what << ": word count " << c;
    occurrences += c;
  }
  SLAM_THROW_IF_NOT(InputError, occurrences <= vocabulary_features)
      << what << ": word counts add up to " << occurrences << ", more than its "
      << vocabulary_features << " vocabulary features";
  return n;
}

void ReadNodes(SqliteDatabase& db, const MapMetadata& m, const MapLoadOptions& options,
               const StoredChecksums& stored, Map* map) {
  SqliteStatement select = db.Prepare(kSelectNodes);
  TableSum sum;
  while (select.Step()) {
    sum.Add(select, 17);
    map->AddNode(ReadNodeRow(select, m, db.path(), options));
  }
  VerifyTable(stored, "nodes", sum, db.path());
}

void ReadLinks(SqliteDatabase& db, const StoredChecksums& stored, Map* map) {
  SqliteStatement select = db.Prepare(kSelectLinks);
  TableSum sum;
  while (select.Step()) {
    sum.Add(select, 5);
    Link link;
    link.from = select.Int(0);
    link.to = select.Int(1);
    const std::string what =
        db.path() + ": link " + std::to_string(link.from) + " -> " + std::to_string(link.to);
    const int64_t type = select.Int(2);
    SLAM_THROW_IF_NOT(InputError, type >= 0 && type <= static_cast<int>(LinkType::kMerged))
        << what << ": unknown link type " << type;
    link.type = static_cast<LinkType>(type);
    link.from_from_to = DecodePose(select.Blob(3), what + " transform");
    link.information = DecodeInformation(select.Blob(4), what + " information");
    map->AddLink(link);
  }
  VerifyTable(stored, "links", sum, db.path());
}

// A stored index that fails its checks is left out with the reason in
// words->index_problem: the vocabulary then rebuilds it (and the caller says
// so); the map itself is still valid.
void ReadWordIndex(SqliteDatabase& db, MapWords* words) {
  SqliteStatement has = db.Prepare("SELECT count(*) FROM sqlite_master WHERE name = 'word_index'");
  if (!has.Step() || has.Int(0) == 0) return;
  SqliteStatement select = db.Prepare("SELECT version, bytes, checksum, state FROM word_index");
  if (!select.Step()) {
    words->index_problem = db.path() + ": the stored vocabulary index is empty";
    return;
  }
  const int64_t version = select.Int(0);
  if (version != kWordIndexVersion) {
    words->index_problem = db.path() + ": stored vocabulary index version " +
                           std::to_string(version) + " (this build reads " +
                           std::to_string(kWordIndexVersion) + ")";
    return;
  }
  std::vector<uint8_t> state = select.Blob(3);
  if (select.Int(1) != static_cast<int64_t>(state.size()) ||
      select.Text(2) != Checksum64Hex(state.data(), state.size())) {
    words->index_problem = db.path() + ": the stored vocabulary index fails its checksum";
    return;
  }
  words->index_state = std::move(state);
}

MapWords ReadWords(SqliteDatabase& db, const MapMetadata& m, int64_t next_word_id,
                   int64_t expected_rows, int64_t file_bytes, const StoredChecksums& stored) {
  MapWords words;
  words.next_word_id = static_cast<WordId>(next_word_id);
  SqliteStatement select = db.Prepare(kSelectWords);
  TableSum sum;
  // The stored form of a word (map.h, MapMetadata::word_storage).
  const WordRowFormat format = WordRowFormatFor(m.descriptor_kind, m.word_storage);
  const bool floats = format == WordRowFormat::kFloat32;
  const int cols = floats ? m.descriptor_cols : static_cast<int>(WordRowBytes(format, m.descriptor_cols));
  const int type = floats ? m.descriptor_cv_type : CV_8U;
  SLAM_THROW_IF_NOT(InputError, cols > 0 && type >= 0)
      << db.path() << ": no descriptor layout for the words";
  const size_t row_bytes = static_cast<size_t>(cols) * CV_ELEM_SIZE(type);
  const int64_t max_rows = std::min<int64_t>(file_bytes / static_cast<int64_t>(row_bytes),
                                             std::numeric_limits<int>::max());
  // Rows go straight into one matrix (a map holds hundreds of thousands),
  // sized by the count recorded at save when the file can hold that many
  // (CheckCounts rejects a map whose count differs).
  int capacity = 0;
  if (expected_rows > 0 && expected_rows <= max_rows) {
    capacity = static_cast<int>(expected_rows);
    words.descriptors.create(capacity, cols, type);
    words.ids.reserve(static_cast<size_t>(capacity));
  }
  int count = 0;
  while (select.Step()) {
    sum.Add(select, 2);
    // Ids are positive, increasing (ORDER BY id) and fit a WordId: a larger
    // id would wrap and break the order the readers of the words rely on.
    const int64_t id = select.Int(0);
    SLAM_THROW_IF_NOT(InputError, id > 0 && id <= std::numeric_limits<WordId>::max() &&
                                      (words.ids.empty() || id > words.ids.back()))
        << db.path() << ": word id " << id << " is out of range or order";
    words.ids.push_back(static_cast<WordId>(id));
    size_t bytes = 0;
    const uint8_t* blob = select.BlobData(1, &bytes);
    SLAM_THROW_IF_NOT(InputError, bytes == row_bytes)
        << db.path() << ": word " << words.ids.back() << ": expected " << row_bytes
        << " bytes for 1x" << cols << ", got " << bytes;
    if (count == capacity) {  // more rows than recorded: grow
      capacity = std::max(16, 2 * capacity);
      cv::Mat grown(capacity, cols, type);
      if (count > 0) std::memcpy(grown.data, words.descriptors.data, count * row_bytes);
      words.descriptors = grown;
    }
    std::memcpy(words.descriptors.ptr(count++), blob, bytes);
  }
  words.descriptors = count == 0 ? cv::Mat() : words.descriptors.rowRange(0, count);
  VerifyTable(stored, "words", sum, db.path());
  ReadWordIndex(db, &words);
  return words;
}

void CheckCounts(const std::map<std::string, std::string>& meta, const Map& map, size_t num_words,
                 const std::string& path) {
  const bool ok = MetaInt(meta, "num_sessions", path) == static_cast<int64_t>(map.sessions().size()) &&
                  MetaInt(meta, "num_nodes", path) == static_cast<int64_t>(map.nodes().size()) &&
                  MetaInt(meta, "num_links", path) == static_cast<int64_t>(map.links().size()) &&
                  MetaInt(meta, "num_words", path) == static_cast<int64_t>(num_words);
  SLAM_THROW_IF_NOT(InputError, ok)
      << path << ": incomplete map (row counts differ from those recorded at save)";
}

}  // namespace

bool IsDuskmapMapFile(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  try {
    CheckFileHeader(path);
    SqliteDatabase db(path, /*read_only=*/true);
    SqliteStatement select = db.Prepare("SELECT count(*) FROM meta WHERE key = 'schema_version'");
    return select.Step() && select.Int(0) == 1;
  } catch (const Error&) {
    return false;
  }
}

void SaveMap(const Map& map, const std::string& path, const MapSaveOptions& options) {
  auto reached = [&](MapSaveStep step) {
    if (options.after_step) options.after_step(step);
  };
  for (const auto& [id, node] : map.nodes()) {
    SLAM_THROW_IF_NOT(InputError, !node.features.has_shared_rows())
        << path << ": node " << id
        << " shares descriptor rows with words held apart (a map loaded for localization); "
           "it cannot be saved";
    SLAM_THROW_IF_NOT(InputError, node.features.has_responses())
        << path << ": node " << id
        << " has no keypoint responses (a map loaded for localization); it cannot be saved";
  }
  // A killed save's temporary file (its process gone) and the fixed name
  // older versions used are removed; this save's own name is unique, so two
  // processes saving to one path never write the same temporary file.
  RemoveStaleSiblings(path, "saving");
  std::remove((path + ".saving").c_str());
  const std::string temp = TemporarySiblingOf(path, "saving");
  // A failed save (a full disk, an unwritable folder) leaves the previous
  // file as it was and no temporary file.
  try {
    {
      SqliteDatabase db(temp, /*read_only=*/false);
      // The temporary file is disposable: no journal; durability comes from
      // the fsync before the rename.
      db.Execute("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF;");
      db.Execute("BEGIN");
      reached(MapSaveStep::kTemporaryCreated);
      db.Execute(kSchema);
      db.Execute(mapdb::kChecksumsSchema);
      WriteMeta(db, map);
      WriteSessions(db, map);
      WriteNodes(db, map);
      WriteLinksAndWords(db, map);
      WriteWordIndex(db, map);
      WriteChecksums(db);
      reached(MapSaveStep::kTablesWritten);
      db.Execute("COMMIT");
    }
    reached(MapSaveStep::kCommitted);
    FsyncPath(temp, /*directory=*/false);
    reached(MapSaveStep::kFlushed);
  } catch (const Error&) {
    std::remove(temp.c_str());
    throw;
  }
  // Without overwrite the name is taken only while it is free; with it, only
  // a duskmap map is replaced (tested right before the rename). PublishFile
  // removes the temporary file when it fails.
  PublishFile(temp, {{options.flag, path},
                     options.overwrite,
                     {"a duskmap map", [](const std::filesystem::path& p) {
                        return IsDuskmapMapFile(p.string());
                      }}});
  FsyncPath(DirectoryOf(path), /*directory=*/true);
  reached(MapSaveStep::kRenamed);
}

namespace {

// What every load checks once the file is open: integrity, schema version,
// feature type.
struct MapHeader {
  std::map<std::string, std::string> meta;
  MapMetadata metadata;
  StoredChecksums checksums;
};

MapHeader ReadHeader(SqliteDatabase& db, const std::string& path, const MapLoadOptions& options) {
  if (options.verify_integrity) CheckIntegrity(db);
  MapHeader header;
  TableSum meta_sum;
  header.meta = ReadMeta(db, &meta_sum);
  // The schema version first: an older map has no checksums and says so.
  const auto version = header.meta.find("schema_version");
  if (version == header.meta.end() || version->second == std::to_string(kMapSchemaVersion)) {
    header.checksums = ReadStoredChecksums(db);
    VerifyTable(header.checksums, "meta", meta_sum, path);
  }
  header.metadata = ReadMetadata(header.meta, path, options);
  return header;
}

// LoadMap and LoadMapAndWords: with `words_apart`, the words are read into
// it and the map keeps only the next word id (options.load_words ignored).
Map LoadMapFrom(const std::string& path, const MapLoadOptions& options, MapWords* words_apart) {
  CheckFileHeader(path);
  SqliteDatabase db(path, /*read_only=*/true);
  MapLoadOptions unchecked = options;
  unchecked.verify_integrity = false;
  MapHeader header;
  try {
    header = ReadHeader(db, path, unchecked);
  } catch (...) {
    if (options.verify_integrity) CheckIntegrity(db);  // a corrupted file says so first
    throw;
  }
  const std::map<std::string, std::string>& meta = header.meta;
  const int64_t next_word_id = MetaInt(meta, "next_word_id", path);
  const bool read_words = words_apart != nullptr || options.load_words;
  // The integrity check and the words (a second connection, read only) run
  // beside the nodes: a six-session map opens in about half the time on two
  // cores. Their errors are thrown once the nodes are read.
  std::future<void> integrity;
  if (options.verify_integrity) {
    integrity = std::async(std::launch::async, [&path] {
      SqliteDatabase check(path, /*read_only=*/true);
      CheckIntegrity(check);
    });
  }
  std::future<MapWords> words_read;
  if (read_words) {
    words_read = std::async(std::launch::async, [&path, &header, next_word_id] {
      SqliteDatabase words_db(path, /*read_only=*/true);
      return ReadWords(words_db, header.metadata, next_word_id,
                       MetaInt(header.meta, "num_words", path), FileBytes(path),
                       header.checksums);
    });
  }
  Map map(header.metadata);
  std::exception_ptr nodes_error;
  try {
    ReadSessions(db, header.checksums, &map);
    ReadNodes(db, header.metadata, options, header.checksums, &map);
    map.ReserveNodeIdsUpTo(MetaInt(meta, "last_node_id", path));
    ReadLinks(db, header.checksums, &map);
  } catch (...) {
    nodes_error = std::current_exception();
  }
  // A corrupted file is reported as such before what reading it ran into.
  if (integrity.valid()) integrity.get();
  MapWords words;
  if (words_read.valid()) words = words_read.get();
  if (nodes_error) std::rethrow_exception(nodes_error);
  size_t num_words = 0;
  if (words_apart == nullptr && options.load_words) {
    num_words = words.ids.size();
    map.SetWords(std::move(words));
  } else {
    if (words_apart != nullptr) {
      *words_apart = std::move(words);
      num_words = words_apart->ids.size();
    } else {
      SqliteStatement count = db.Prepare("SELECT count(*) FROM words");
      SLAM_THROW_IF_NOT(InputError, count.Step()) << path << ": cannot count the words";
      num_words = static_cast<size_t>(count.Int(0));
    }
    MapWords empty;
    empty.next_word_id = static_cast<WordId>(next_word_id);
    map.SetWords(std::move(empty));
  }
  CheckCounts(meta, map, num_words, path);
  return map;
}

}  // namespace

Map LoadMap(const std::string& path, const MapLoadOptions& options) {
  return LoadMapFrom(path, options, /*words_apart=*/nullptr);
}

MapAndWords LoadMapAndWords(const std::string& path, const MapLoadOptions& options) {
  MapAndWords loaded;
  loaded.map = LoadMapFrom(path, options, &loaded.words);
  if (options.share_node_rows_with_words) ShareNodeRowsWithWords(loaded.words, &loaded.map);
  return loaded;
}

MapWords LoadMapWords(const std::string& path, const MapLoadOptions& options) {
  CheckFileHeader(path);
  SqliteDatabase db(path, /*read_only=*/true);
  const MapHeader header = ReadHeader(db, path, options);
  const std::map<std::string, std::string>& meta = header.meta;
  MapWords words = ReadWords(db, header.metadata, MetaInt(meta, "next_word_id", path),
                             MetaInt(meta, "num_words", path), FileBytes(path),
                             header.checksums);
  SLAM_THROW_IF_NOT(InputError, MetaInt(meta, "num_words", path) ==
                                    static_cast<int64_t>(words.ids.size()))
      << path << ": incomplete map (row counts differ from those recorded at save)";
  return words;
}

}  // namespace duskmap
