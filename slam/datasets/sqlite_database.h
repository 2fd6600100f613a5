// A read-only SQLite connection and prepared statements, with every failure
// reported as InputError naming the database file.
#pragma once

#include <cstdint>
#include <set>
#include <string>

struct sqlite3;
struct sqlite3_stmt;

namespace duskmap {

class SqliteStatement {
 public:
  SqliteStatement(sqlite3_stmt* statement, std::string where);
  ~SqliteStatement();
  SqliteStatement(SqliteStatement&& other) noexcept;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;
  SqliteStatement& operator=(SqliteStatement&&) = delete;

  void BindInt64(int index, int64_t value);  // 1-based, like SQLite
  // Advances to the next row; false when done. Throws InputError on failure.
  bool Step();
  void Reset();

  bool IsNull(int column) const;
  int64_t Int64(int column) const;
  double Double(int column) const;
  std::string Text(int column) const;
  // Blob bytes, valid until the next Step/Reset; size 0 (and nullptr) for NULL.
  const uint8_t* Blob(int column, size_t* size) const;

 private:
  sqlite3_stmt* statement_;
  std::string where_;
};

class SqliteDatabase {
 public:
  // Opens read-only; throws InputError "<path>: ..." when the file is missing
  // or is not an SQLite database.
  explicit SqliteDatabase(const std::string& path);
  ~SqliteDatabase();
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  SqliteStatement Prepare(const std::string& sql) const;
  bool HasTable(const std::string& table) const;
  std::set<std::string> Columns(const std::string& table) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

}  // namespace duskmap
