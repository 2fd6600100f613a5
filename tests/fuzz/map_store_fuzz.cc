// libFuzzer target for duskmap's map store: LoadMap, LoadMapAndWords and
// IsDuskmapMapFile on a file made from the input, then what a localizer does
// with a loaded map (the vocabulary imported with its stored index, every
// node's features decoded). The input is either
//  - a whole map file (it starts with "SQLite format 3"), or
//  - edits to one of two small valid maps the target saves at start-up
//    (binary words with a stored KD-forest index; 8-bit quantized float
//    nodes and words):
//      byte 0: flags (bit 0: the float map, bit 1: record the table checksums
//              anew after the edits, as a map written with those values would
//              have them, so that the checks behind them are reached;
//              bit 2: load without the integrity check; bit 3: expect
//              feature type "brief"; bit 4: keep node rows apart from the
//              words; bit 5: drop keypoint responses)
//      then edits, each 4 bytes (table, column, row, operation) and a field
//      (little-endian uint16 length + bytes): set the value to a blob,
//      integer, real, text or NULL, overwrite bytes inside it, resize it,
//      add to it, delete or duplicate the row, or drop the table.
// Loading may throw duskmap::Error; anything else (a crash, a sanitizer
// report, an abort) is a bug, as is a loaded map that breaks what map.h
// promises (words in increasing id order, one stored row per word).
// With DUSKMAP_FUZZ_WRITE_SEEDS=<dir>, the target writes seed inputs there.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <sqlite3.h>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/map/map.h"
#include "slam/map/map_store.h"
#include "slam/map/map_vocabulary.h"
#include "slam/vocabulary/vocabulary.h"
#if __has_include("slam/map/table_checksums.h")
#include "slam/map/table_checksums.h"
#define DUSKMAP_FUZZ_HAS_TABLE_CHECKSUMS 1
#endif

namespace {

// DUSKMAP_FUZZ_VERBOSE=1: print each expected error (to see how far an input gets).
void Expected(const duskmap::Error& e) {
  static const bool verbose = std::getenv("DUSKMAP_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "%s: %s\n", "map_store_fuzz", e.what());
}

using Bytes = std::vector<uint8_t>;

std::string TempPath() {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/duskmap_map_fuzz_" + std::to_string(getpid()) + ".db";
}

Bytes ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteFileBytes(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void RemoveMapFiles(const std::string& path) {
  for (const char* suffix : {"", "-journal", "-wal", "-shm", ".saving"}) {
    std::remove((path + suffix).c_str());
  }
}

duskmap::VocabularyOptions VocabularyOptionsFor(bool float_map) {
  duskmap::VocabularyOptions options;
  options.max_features_per_node = 0;  // quantize every row, whatever the count
  if (float_map) options.index.float_storage = duskmap::DescriptorStorage::kUint8;
  return options;
}

// A small valid map: two sessions of three nodes, odometry links and one
// loop closure, its words from a real vocabulary and their stored index.
duskmap::Map MakeSeedMap(bool float_map) {
  using namespace duskmap;
  Rng rng(float_map ? 11 : 7);
  cv::setRNGSeed(float_map ? 11 : 7);
  const DescriptorStorage storage = float_map ? DescriptorStorage::kUint8 : DescriptorStorage::kFloat32;
  MapMetadata metadata;
  metadata.feature_type = float_map ? "surf" : "orb";
  metadata.feature_parameters_json = R"({"max_features":24})";
  metadata.engine_parameters_json = R"({"mapping":{}})";
  metadata.descriptor_storage = storage;
  metadata.word_storage = storage;
  Map map(metadata);
  const VocabularyOptions vocabulary_options = VocabularyOptionsFor(float_map);
  Vocabulary vocabulary(vocabulary_options);
  std::uniform_real_distribution<float> u(0.f, 300.f);
  cv::Mat shared(8, float_map ? 64 : 32, float_map ? CV_32F : CV_8U);
  cv::randu(shared, 0, float_map ? 1 : 255);
  NodeId id = 1;
  for (SessionId s = 0; s < 2; ++s) {
    map.AddSession(s == 0 ? "1" : "A", s == 0 ? std::optional<std::string>("16:46") : std::nullopt);
    for (int i = 0; i < 3; ++i, ++id) {
      MapNode n;
      n.id = id;
      n.session = s;
      n.frame_index = i * 2;
      n.timestamp_s = 1700000000.0 + id;
      n.map_from_body = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random());
      n.odom_from_body = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random());
      n.body_from_camera = Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, 0, 0.2));
      n.camera = PinholeCamera{320, 240, 260.0, 261.0, 159.5, 119.5};
      if (id % 2) n.truth_from_camera = n.map_from_body * n.body_from_camera;
      FrameFeatures f;
      const int rows = 12;
      for (int k = 0; k < rows; ++k) {
        f.keypoints.emplace_back(u(rng), u(rng), 7.f + k % 5, u(rng), 1.f / (k + 1), 0, -1);
        f.points_in_camera.push_back(k % 5 == 0
                                         ? Eigen::Vector3f(Eigen::Vector3f::Constant(std::nanf("")))
                                         : Eigen::Vector3f(Eigen::Vector3f::Random()));
      }
      f.kind = float_map ? DescriptorKind::kFloat : DescriptorKind::kBinary;
      f.descriptors = cv::Mat(rows, shared.cols, shared.type());
      cv::randu(f.descriptors, 0, float_map ? 1 : 255);
      shared.rowRange(0, 4).copyTo(f.descriptors.rowRange(0, 4));  // words seen again
      vocabulary.AddNode(id, f);
      n.features = CompactFeatures::Encode(f, storage);
      n.vocabulary_features = rows;
      map.AddNode(n);
      if (i > 0) {
        Link link;
        link.from = id - 1;
        link.to = id;
        link.from_from_to = map.node(id - 1).map_from_body.Inverse() * map.node(id).map_from_body;
        link.information = Information6d::Identity() * (100.0 + id);
        map.AddLink(link);
      }
    }
  }
  Link loop;
  loop.from = id - 1;
  loop.to = 2;
  loop.type = LinkType::kLoopClosure;
  loop.from_from_to = Rigid3d(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(0.1, 0.2, 0.3));
  loop.information = Information6d::Identity() * 50.0;
  map.AddLink(loop);
  SetMapVocabulary(vocabulary.Export(), &map);
  Vocabulary imported(vocabulary_options);  // the index a localizer restores
  imported.Import(MapVocabularySnapshot(map));
  map.SetWordIndexState(imported.SaveIndexState());
  return map;
}

const Bytes& SeedMapFile(bool float_map) {
  static const Bytes files[2] = {
      [] {
        const std::string path = TempPath() + ".seed";
        duskmap::SaveMap(MakeSeedMap(false), path);
        Bytes bytes = ReadFileBytes(path);
        RemoveMapFiles(path);
        return bytes;
      }(),
      [] {
        const std::string path = TempPath() + ".seed";
        duskmap::SaveMap(MakeSeedMap(true), path);
        Bytes bytes = ReadFileBytes(path);
        RemoveMapFiles(path);
        return bytes;
      }()};
  return files[float_map ? 1 : 0];
}

// ---- edits ----------------------------------------------------------------

class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool Byte(uint8_t* b) {
    if (offset_ >= size_) return false;
    *b = data_[offset_++];
    return true;
  }
  bool Field(Bytes* field) {
    if (offset_ + 2 > size_) return false;
    const size_t length = data_[offset_] | (size_t{data_[offset_ + 1]} << 8);
    offset_ += 2;
    const size_t n = std::min(length, size_ - offset_);
    field->assign(data_ + offset_, data_ + offset_ + n);
    offset_ += n;
    return true;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

std::vector<std::string> Strings(sqlite3* db, const std::string& sql, int column) {
  std::vector<std::string> out;
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) == SQLITE_OK) {
    while (sqlite3_step(s) == SQLITE_ROW) {
      const unsigned char* text = sqlite3_column_text(s, column);
      out.emplace_back(text ? reinterpret_cast<const char*>(text) : "");
    }
  }
  sqlite3_finalize(s);
  return out;
}

std::string Quoted(const std::string& name) {
  std::string q = "\"";
  for (char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

int64_t LittleEndian(const Bytes& field) {
  uint64_t v = 0;
  for (size_t i = 0; i < std::min<size_t>(8, field.size()); ++i) v |= uint64_t{field[i]} << (8 * i);
  if (!field.empty() && field.size() < 8 && (field.back() & 0x80)) {  // sign-extend
    v |= ~uint64_t{0} << (8 * field.size());
  }
  return static_cast<int64_t>(v);
}

// Runs `sql` with ?1 = the row id and ?2 bound by `bind` (if any).
template <typename Bind>
void Run(sqlite3* db, const std::string& sql, int64_t rowid, Bind bind) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
    sqlite3_finalize(s);
    return;
  }
  sqlite3_bind_int64(s, 1, rowid);
  bind(s);
  sqlite3_step(s);
  sqlite3_finalize(s);
}

void ApplyEdit(sqlite3* db, uint8_t table_pick, uint8_t column_pick, uint8_t row_pick,
               uint8_t operation, const Bytes& field) {
  const std::vector<std::string> tables =
      Strings(db, "SELECT name FROM sqlite_master WHERE type='table' ORDER BY name", 0);
  if (tables.empty()) return;
  const std::string table = Quoted(tables[table_pick % tables.size()]);
  const std::vector<std::string> columns = Strings(db, "PRAGMA table_info(" + table + ")", 1);
  const std::vector<std::string> rowids =
      Strings(db, "SELECT rowid FROM " + table + " ORDER BY rowid", 0);
  if (columns.empty()) return;
  const std::string column = Quoted(columns[column_pick % columns.size()]);
  const int64_t rowid = rowids.empty() ? 0 : std::atoll(rowids[row_pick % rowids.size()].c_str());
  const std::string set = "UPDATE " + table + " SET " + column + " = ?2 WHERE rowid = ?1";
  auto bind_bytes = [&field](sqlite3_stmt* s) {
    sqlite3_bind_blob(s, 2, field.data(), static_cast<int>(field.size()), SQLITE_TRANSIENT);
  };
  switch (operation % 12) {
    case 0:
      Run(db, set, rowid, bind_bytes);
      break;
    case 1:
      Run(db, set, rowid, [&](sqlite3_stmt* s) { sqlite3_bind_int64(s, 2, LittleEndian(field)); });
      break;
    case 2: {
      double v = 0.0;
      std::memcpy(&v, field.data(), std::min<size_t>(8, field.size()));
      Run(db, set, rowid, [&](sqlite3_stmt* s) { sqlite3_bind_double(s, 2, v); });
      break;
    }
    case 3:
      Run(db, set, rowid, [&](sqlite3_stmt* s) {
        sqlite3_bind_text(s, 2, reinterpret_cast<const char*>(field.data()),
                          static_cast<int>(field.size()), SQLITE_TRANSIENT);
      });
      break;
    case 4:
      Run(db, set, rowid, [](sqlite3_stmt* s) { sqlite3_bind_null(s, 2); });
      break;
    case 5:    // overwrite bytes inside the value: offset (2 bytes), then the bytes
    case 6: {  // resize the value to a length (2 bytes), zero-filled
      sqlite3_stmt* s = nullptr;
      Bytes value;
      int type = SQLITE_BLOB;
      const std::string get = "SELECT " + column + " FROM " + table + " WHERE rowid = ?1";
      if (sqlite3_prepare_v2(db, get.c_str(), -1, &s, nullptr) == SQLITE_OK) {
        sqlite3_bind_int64(s, 1, rowid);
        if (sqlite3_step(s) == SQLITE_ROW) {
          type = sqlite3_column_type(s, 0);
          const auto* p = static_cast<const uint8_t*>(sqlite3_column_blob(s, 0));
          value.assign(p, p + sqlite3_column_bytes(s, 0));
        }
      }
      sqlite3_finalize(s);
      const size_t at = field.size() >= 2 ? (field[0] | (size_t{field[1]} << 8)) : 0;
      if (operation % 12 == 5) {
        const size_t offset = value.empty() ? 0 : at % (value.size() + 1);
        const size_t n = field.size() > 2 ? field.size() - 2 : 0;
        if (offset + n > value.size()) value.resize(offset + n);
        std::copy(field.begin() + std::min<size_t>(2, field.size()), field.end(),
                  value.begin() + static_cast<std::ptrdiff_t>(offset));
      } else {
        value.resize(at);
      }
      Run(db, set, rowid, [&](sqlite3_stmt* st) {
        if (type == SQLITE_TEXT) {
          sqlite3_bind_text(st, 2, reinterpret_cast<const char*>(value.data()),
                            static_cast<int>(value.size()), SQLITE_TRANSIENT);
        } else {
          sqlite3_bind_blob(st, 2, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
        }
      });
      break;
    }
    case 7:  // add a signed amount to a number (or to a text that holds one)
      Run(db, "UPDATE " + table + " SET " + column + " = " + column + " + ?2 WHERE rowid = ?1",
          rowid, [&](sqlite3_stmt* s) { sqlite3_bind_int64(s, 2, LittleEndian(field)); });
      break;
    case 8:
      Run(db, "DELETE FROM " + table + " WHERE rowid = ?1", rowid, [](sqlite3_stmt*) {});
      break;
    case 9:  // a copy of the row under a new row id (unique keys may refuse it)
      Run(db, "INSERT INTO " + table + " SELECT * FROM " + table + " WHERE rowid = ?1", rowid,
          [](sqlite3_stmt*) {});
      break;
    case 10:
      if (!field.empty() && field[0] == 'D') sqlite3_exec(db, ("DROP TABLE " + table).c_str(),
                                                          nullptr, nullptr, nullptr);
      break;
    default:  // the value as text of a number written in the field
      Run(db, set, rowid, [&](sqlite3_stmt* s) {
        const std::string text = std::to_string(LittleEndian(field));
        sqlite3_bind_text(s, 2, text.c_str(), -1, SQLITE_TRANSIENT);
      });
      break;
  }
}

void WriteEdited(const uint8_t* data, size_t size, const std::string& path) {
  const uint8_t flags = size > 0 ? data[0] : 0;
  const Bytes& seed = SeedMapFile(flags & 1);
  WriteFileBytes(path, seed.data(), seed.size());
  Reader reader(data + (size > 0 ? 1 : 0), size > 0 ? size - 1 : 0);
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) {
    sqlite3_close(db);
    return;
  }
  sqlite3_exec(db, "PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; BEGIN;", nullptr, nullptr,
               nullptr);
  for (int edit = 0; edit < 16; ++edit) {
    uint8_t t, c, r, op;
    Bytes field;
    if (!reader.Byte(&t) || !reader.Byte(&c) || !reader.Byte(&r) || !reader.Byte(&op)) break;
    reader.Field(&field);
    ApplyEdit(db, t, c, r, op, field);
  }
  sqlite3_exec(db, "COMMIT;", nullptr, nullptr, nullptr);
  sqlite3_close(db);
#ifdef DUSKMAP_FUZZ_HAS_TABLE_CHECKSUMS
  if (flags & 2) {
    try {
      duskmap::mapdb::SqliteDatabase map_db(path, /*read_only=*/false);
      map_db.Execute("DELETE FROM checksums");
      duskmap::mapdb::WriteChecksums(map_db);
    } catch (const duskmap::Error&) {
      // A table the checksums read is gone or unreadable: the load says so.
    }
  }
#endif
}

// ---- loading --------------------------------------------------------------

void CheckWords(const duskmap::MapWords& words) {
  if (static_cast<size_t>(words.descriptors.rows) != words.ids.size() && !words.ids.empty()) {
    std::abort();
  }
  for (size_t i = 1; i < words.ids.size(); ++i) {
    if (!(words.ids[i] > words.ids[i - 1])) std::abort();
  }
}

void LoadAll(const std::string& path, uint8_t flags) {
  using namespace duskmap;
  MapLoadOptions options;
  options.verify_integrity = !(flags & 4);
  if (flags & 8) options.expected_feature_type = "brief";
  try {
    IsDuskmapMapFile(path);
  } catch (const Error& e) {
    Expected(e);
  }
  try {
    const Map map = LoadMap(path, options);
    CheckWords(map.words());
    for (const auto& [id, node] : map.nodes()) {
      if (node.session < 0 || static_cast<size_t>(node.session) >= map.sessions().size()) {
        std::abort();
      }
      const FrameFeatures features = node.features.Decode();
      if (features.keypoints.size() != node.features.size()) std::abort();
    }
  } catch (const Error& e) {
    Expected(e);
  }
  options.share_node_rows_with_words = !(flags & 16);
  options.keep_keypoint_responses = !(flags & 32);
  try {
    const MapAndWords loaded = LoadMapAndWords(path, options);
    CheckWords(loaded.words);
    const bool float_map = loaded.map.metadata().descriptor_kind == DescriptorKind::kFloat;
    Vocabulary vocabulary(VocabularyOptionsFor(float_map));
    vocabulary.Import(MapVocabularySnapshot(loaded.map, loaded.words));
    for (const auto& [id, node] : loaded.map.nodes()) node.features.Decode(&vocabulary);
  } catch (const Error& e) {
    Expected(e);
  }
}

void AppendField(const Bytes& bytes, Bytes* out) {
  out->push_back(static_cast<uint8_t>(bytes.size() & 0xFF));
  out->push_back(static_cast<uint8_t>(bytes.size() >> 8));
  out->insert(out->end(), bytes.begin(), bytes.end());
}

void WriteSeed(const std::string& dir, const std::string& name, const Bytes& bytes) {
  WriteFileBytes(dir + "/" + name, bytes.data(), bytes.size());
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  SeedMapFile(false);  // build both maps once, before the first input
  if (const char* dir = std::getenv("DUSKMAP_FUZZ_WRITE_SEEDS")) {
    WriteSeed(dir, "map_binary.db", SeedMapFile(false));
    WriteSeed(dir, "map_float.db", SeedMapFile(true));
    WriteSeed(dir, "edits_none_binary", Bytes{0x00});
    WriteSeed(dir, "edits_none_float", Bytes{0x01});
    // Resealed: bytes inside a node's descriptors blob (table "nodes" is
    // fourth by name: checksums, links, meta, nodes, sessions, word_index,
    // words); a word row cut short; a meta value changed.
    Bytes a = {0x02, 3, 12, 1, 5};
    AppendField(Bytes{4, 0, 0xFF, 0x00, 0x7F}, &a);
    WriteSeed(dir, "edits_node_descriptors", a);
    Bytes b = {0x03, 6, 1, 2, 6};
    AppendField(Bytes{10, 0}, &b);
    WriteSeed(dir, "edits_word_row", b);
    Bytes c = {0x02, 2, 1, 3, 11};
    AppendField(Bytes{0x00, 0xCA, 0x9A, 0x3B}, &c);  // 1e9 as text
    WriteSeed(dir, "edits_meta_value", c);
    Bytes d = {0x06, 5, 3, 0, 7};
    AppendField(Bytes{0x01}, &d);
    WriteSeed(dir, "edits_word_index", d);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = TempPath();
  RemoveMapFiles(path);
  uint8_t flags = 0;
  if (size >= 15 && std::memcmp(data, "SQLite format 3", 15) == 0) {
    WriteFileBytes(path, data, size);
  } else {
    WriteEdited(data, size, path);
    flags = size > 0 ? data[0] : 0;
  }
  LoadAll(path, flags);
  RemoveMapFiles(path);
  return 0;
}
