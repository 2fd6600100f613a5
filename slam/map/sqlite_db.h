// Thin RAII wrapper over the SQLite C API used by the map store: a database
// handle and prepared statements with typed binds and column reads (in
// namespace mapdb: the datasets module has its own wrapper). Errors
// throw InputError naming the file and SQLite's message.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace duskmap::mapdb {

class SqliteStatement;

class SqliteDatabase {
 public:
  // Opens (read-only, or read-write creating it) the database at path.
  SqliteDatabase(const std::string& path, bool read_only);
  ~SqliteDatabase();
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  void Execute(const std::string& sql);
  SqliteStatement Prepare(const std::string& sql);
  const std::string& path() const { return path_; }
  sqlite3* handle() { return db_; }
  // Throws InputError "<path>: <what>: <sqlite message>" when rc is an error.
  void ThrowIfError(int rc, const std::string& what);

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

class SqliteStatement {
 public:
  SqliteStatement(SqliteDatabase* db, sqlite3_stmt* statement) : db_(db), statement_(statement) {}
  ~SqliteStatement();
  SqliteStatement(SqliteStatement&& other) noexcept;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  // Binds are 1-based, as in SQLite.
  void BindInt(int index, int64_t value);
  void BindDouble(int index, double value);
  void BindText(int index, const std::string& value);
  void BindBlob(int index, const std::vector<uint8_t>& value);
  void BindNull(int index);
  // Steps once: true when a row is available, false when done.
  bool Step();
  // Steps to completion and resets for the next binds.
  void Run();
  void Reset();

  // Columns are 0-based, as in SQLite.
  bool IsNull(int column) const;
  int64_t Int(int column) const;
  double Double(int column) const;
  std::string Text(int column) const;
  std::vector<uint8_t> Blob(int column) const;
  // The blob without a copy: valid until the next Step, Reset or column
  // access of this statement. `*bytes` gets its size (nullptr when empty).
  const uint8_t* BlobData(int column, size_t* bytes) const;
  // A 64-bit checksum of the current row's first `num_columns` values (their
  // storage types and bytes), for the map's table checksums.
  uint64_t RowChecksum(int num_columns) const;

 private:
  SqliteDatabase* db_;
  sqlite3_stmt* statement_;
};

}  // namespace duskmap::mapdb
