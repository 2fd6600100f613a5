// libFuzzer target for the RTAB-Map database reader. The input describes a
// small database that the target writes with SQLite, then reads back through
// OpenRtabmapDatabase (every session, every frame, skip_bad_frames on):
//   byte 0: flags (bit 0: no Admin table, bit 1: no Data table, bit 2: Node
//           without ground_truth_pose column, bit 3: read without skipping)
//   then fields, each a little-endian uint16 length + bytes (0xFFFF = NULL):
//   version, then per node (at most 4): map_id (1 byte), stamp (8-byte
//   double), pose, ground_truth_pose, image, depth, calibration.
// An input that starts with "SQLite format 3" is written as the database file
// itself. Any outcome other than a value or duskmap::Error is a bug.
// With DUSKMAP_FUZZ_WRITE_SEEDS=<dir>, the target writes seed inputs there.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <sqlite3.h>

#include "slam/core/check.h"
#include "slam/datasets/rtabmap_db_reader.h"
#include "slam/datasets/rvl_codec.h"

namespace {

using Bytes = std::vector<uint8_t>;

class Fields {
 public:
  Fields(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool Next(std::optional<Bytes>* field) {
    if (offset_ + 2 > size_) return false;
    const size_t length = data_[offset_] | (size_t{data_[offset_ + 1]} << 8);
    offset_ += 2;
    if (length == 0xFFFF) {
      field->reset();
      return true;
    }
    const size_t n = std::min(length, size_ - offset_);
    *field = Bytes(data_ + offset_, data_ + offset_ + n);
    offset_ += n;
    return true;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

void Exec(sqlite3* db, const char* sql) { sqlite3_exec(db, sql, nullptr, nullptr, nullptr); }

void BindField(sqlite3_stmt* statement, int index, const std::optional<Bytes>& field) {
  if (!field) {
    sqlite3_bind_null(statement, index);
  } else {
    sqlite3_bind_blob(statement, index, field->data(), static_cast<int>(field->size()),
                      SQLITE_TRANSIENT);
  }
}

void WriteStructured(const uint8_t* data, size_t size, const std::string& path) {
  const uint8_t flags = size > 0 ? data[0] : 0;
  Fields fields(data + (size > 0 ? 1 : 0), size > 0 ? size - 1 : 0);
  sqlite3* db = nullptr;
  sqlite3_open(path.c_str(), &db);
  Exec(db, "PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; BEGIN;");
  std::optional<Bytes> field;
  if (!(flags & 1)) {
    Exec(db, "CREATE TABLE Admin(version TEXT)");
    fields.Next(&field);
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO Admin VALUES(?)", -1, &s, nullptr);
    if (field) sqlite3_bind_text(s, 1, reinterpret_cast<const char*>(field->data()),
                                 static_cast<int>(field->size()), SQLITE_TRANSIENT);
    sqlite3_step(s);
    sqlite3_finalize(s);
  }
  Exec(db, (flags & 4) ? "CREATE TABLE Node(id, map_id, weight, stamp, pose)"
                       : "CREATE TABLE Node(id, map_id, weight, stamp, pose, ground_truth_pose)");
  if (!(flags & 2)) Exec(db, "CREATE TABLE Data(id, image, depth, calibration)");
  sqlite3_stmt* node = nullptr;
  sqlite3_stmt* row = nullptr;
  sqlite3_prepare_v2(db, (flags & 4) ? "INSERT INTO Node VALUES(?,?,0,?,?)"
                                     : "INSERT INTO Node VALUES(?,?,0,?,?,?)",
                     -1, &node, nullptr);
  sqlite3_prepare_v2(db, "INSERT INTO Data VALUES(?,?,?,?)", -1, &row, nullptr);
  for (int id = 1; id <= 4; ++id) {
    std::optional<Bytes> f[7];
    bool complete = true;
    for (auto& x : f) complete = complete && fields.Next(&x);
    if (!complete) break;
    double stamp = 0.0;
    if (f[1] && f[1]->size() >= 8) std::memcpy(&stamp, f[1]->data(), 8);
    sqlite3_bind_int(node, 1, id);
    sqlite3_bind_int(node, 2, f[0] && !f[0]->empty() ? (*f[0])[0] % 3 : 0);
    sqlite3_bind_double(node, 3, stamp);
    BindField(node, 4, f[2]);
    if (!(flags & 4)) BindField(node, 5, f[3]);
    sqlite3_step(node);
    sqlite3_reset(node);
    if (row) {
      sqlite3_bind_int(row, 1, id);
      for (int i = 0; i < 3; ++i) BindField(row, 2 + i, f[4 + i]);
      sqlite3_step(row);
      sqlite3_reset(row);
    }
  }
  sqlite3_finalize(node);
  sqlite3_finalize(row);
  Exec(db, "COMMIT;");
  sqlite3_close(db);
}

void ReadAll(const std::string& path, bool skip) {
  duskmap::DatasetReadOptions options;
  options.skip_bad_frames = skip;
  options.skip_log = std::make_shared<duskmap::SkipLog>();
  try {
    const auto reader = duskmap::OpenRtabmapDatabase(path, options);
    for (const duskmap::SessionInfo& info : reader->Sessions()) {
      const auto session = reader->OpenSession(info.name);
      while (true) {
        try {
          const std::optional<duskmap::RgbdFrame> frame = session->Next();
          if (!frame) break;
          if (frame->bgr.size() != frame->depth_m.size() || !frame->camera.IsValid()) std::abort();
        } catch (const duskmap::InputError&) {
        }
      }
    }
  } catch (const duskmap::Error&) {
  }
}

void AppendField(const Bytes& bytes, Bytes* out) {
  out->push_back(static_cast<uint8_t>(bytes.size() & 0xFF));
  out->push_back(static_cast<uint8_t>(bytes.size() >> 8));
  out->insert(out->end(), bytes.begin(), bytes.end());
}

template <typename T>
void AppendPod(const T& value, Bytes* out) {
  const auto* p = reinterpret_cast<const uint8_t*>(&value);
  out->insert(out->end(), p, p + sizeof(T));
}

// A well-formed two-node input: 16x12 JPEG, RVL depth, mono calibration.
Bytes SeedInput(bool png_depth) {
  cv::Mat bgr(12, 16, CV_8UC3);
  cv::randu(bgr, 0, 255);
  cv::Mat depth(12, 16, CV_16UC1);
  cv::randu(depth, 0, 3000);
  depth.col(0).setTo(0);
  std::vector<uint8_t> jpeg, png;
  cv::imencode(".jpg", bgr, jpeg);
  cv::imencode(".png", depth, png);
  const Bytes rvl = duskmap::EncodeRvlBlob(depth);
  Bytes calibration;
  for (int v : {0, 23, 8, 0, 16, 12, 9, 0, 0, 0, 12}) AppendPod<int32_t>(v, &calibration);
  for (double v : {13.0, 0.0, 7.5, 0.0, 13.0, 5.5, 0.0, 0.0, 1.0}) AppendPod(v, &calibration);
  Bytes identity;
  for (float v : {1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f}) AppendPod(v, &identity);
  calibration.insert(calibration.end(), identity.begin(), identity.end());
  Bytes input = {0};
  AppendField(Bytes{'0', '.', '2', '3', '.', '8'}, &input);
  for (int node = 0; node < 2; ++node) {
    AppendField(Bytes{0}, &input);
    Bytes stamp;
    AppendPod(1700000000.0 + node, &stamp);
    AppendField(stamp, &input);
    AppendField(identity, &input);
    AppendField(identity, &input);
    AppendField(jpeg, &input);
    AppendField(png_depth ? Bytes(png) : rvl, &input);
    AppendField(calibration, &input);
  }
  return input;
}

std::string TempPath() {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/duskmap_fuzz_" + std::to_string(getpid()) + ".db";
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* dir = std::getenv("DUSKMAP_FUZZ_WRITE_SEEDS")) {
    for (int i = 0; i < 2; ++i) {
      const Bytes seed = SeedInput(i == 1);
      std::ofstream(std::string(dir) + "/seed" + std::to_string(i), std::ios::binary)
          .write(reinterpret_cast<const char*>(seed.data()), seed.size());
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = TempPath();
  std::remove(path.c_str());
  if (size >= 15 && std::memcmp(data, "SQLite format 3", 15) == 0) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), size);
  } else {
    WriteStructured(data, size, path);
  }
  ReadAll(path, size == 0 || !(data[0] & 8));
  std::remove(path.c_str());
  return 0;
}
