// Helpers shared by the datasets tests: the shared RTAB-Map fixtures, temp
// folders, and SQL edits that build corrupt copies of a database.
#pragma once

#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "slam/io/dataset_reader.h"
#include "tests/testing/temp_dir.h"

namespace duskmap::testing {

namespace fs = std::filesystem;

// ../shared/data/rtabmap, or "" when absent.
inline std::string SharedRtabmapDir() {
  const fs::path dir = fs::path(DUSKMAP_SHARED_DIR) / "data" / "rtabmap";
  return fs::is_directory(dir) ? dir.string() : "";
}

#define SKIP_WITHOUT_SHARED_RTABMAP(dir)                                               \
  const std::string dir = ::duskmap::testing::SharedRtabmapDir();                      \
  if (dir.empty()) GTEST_SKIP() << "shared RTAB-Map fixtures not found under "         \
                                << DUSKMAP_SHARED_DIR << "/data/rtabmap; skipping"

// A fresh empty folder under the process's temporary root, named after the current test.
inline std::string MakeTempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return ProcessTempDir("datasets_" + std::string(info->test_suite_name()) + "_" + info->name());
}

// Copies a file or folder, making the copy writable.
inline std::string CopyWritable(const std::string& from, const std::string& to) {
  fs::copy(from, to, fs::copy_options::recursive);
  if (fs::is_directory(to)) {
    for (const auto& entry : fs::recursive_directory_iterator(to)) {
      fs::permissions(entry.path(), fs::perms::owner_write, fs::perm_options::add);
    }
  }
  fs::permissions(to, fs::perms::owner_write, fs::perm_options::add);
  return to;
}

inline void ExecSql(const std::string& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << sql << ": " << message;
}

inline void SetBlob(const std::string& db_path, const std::string& table,
                    const std::string& column, int64_t id, const std::vector<uint8_t>& bytes) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* statement = nullptr;
  const std::string sql = "UPDATE " + table + " SET " + column + " = ? WHERE id = ?";
  ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr), SQLITE_OK);
  sqlite3_bind_blob(statement, 1, bytes.data(), static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
  sqlite3_bind_int64(statement, 2, id);
  EXPECT_EQ(sqlite3_step(statement), SQLITE_DONE);
  sqlite3_finalize(statement);
  sqlite3_close(db);
}

inline std::vector<uint8_t> GetBlob(const std::string& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  std::vector<uint8_t> bytes;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return bytes;
  }
  sqlite3_stmt* statement = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr) == SQLITE_OK &&
      sqlite3_step(statement) == SQLITE_ROW) {
    const auto* data = static_cast<const uint8_t*>(sqlite3_column_blob(statement, 0));
    bytes.assign(data, data + sqlite3_column_bytes(statement, 0));
  }
  sqlite3_finalize(statement);
  sqlite3_close(db);
  return bytes;
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

inline void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Every frame of a session.
inline std::vector<RgbdFrame> ReadAllFrames(SessionReader& session) {
  std::vector<RgbdFrame> frames;
  while (std::optional<RgbdFrame> frame = session.Next()) frames.push_back(std::move(*frame));
  return frames;
}

}  // namespace duskmap::testing
