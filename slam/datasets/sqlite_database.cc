#include "slam/datasets/sqlite_database.h"

#include <filesystem>

#include <sqlite3.h>

#include "slam/core/check.h"

namespace duskmap {

SqliteStatement::SqliteStatement(sqlite3_stmt* statement, std::string where)
    : statement_(statement), where_(std::move(where)) {}

SqliteStatement::~SqliteStatement() {
  if (statement_) sqlite3_finalize(statement_);
}

SqliteStatement::SqliteStatement(SqliteStatement&& other) noexcept
    : statement_(other.statement_), where_(std::move(other.where_)) {
  other.statement_ = nullptr;
}

void SqliteStatement::BindInt64(int index, int64_t value) {
  SLAM_CHECK(sqlite3_bind_int64(statement_, index, value) == SQLITE_OK);
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  SLAM_THROW(InputError) << where_ << ": SQLite error: "
                         << sqlite3_errmsg(sqlite3_db_handle(statement_));
  return false;
}

void SqliteStatement::Reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

bool SqliteStatement::IsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

int64_t SqliteStatement::Int64(int column) const {
  return sqlite3_column_int64(statement_, column);
}

double SqliteStatement::Double(int column) const {
  return sqlite3_column_double(statement_, column);
}

std::string SqliteStatement::Text(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  if (!text) return "";
  return std::string(reinterpret_cast<const char*>(text),
                     static_cast<size_t>(sqlite3_column_bytes(statement_, column)));
}

const uint8_t* SqliteStatement::Blob(int column, size_t* size) const {
  const void* data = sqlite3_column_blob(statement_, column);
  *size = data ? static_cast<size_t>(sqlite3_column_bytes(statement_, column)) : 0;
  return static_cast<const uint8_t*>(data);
}

SqliteDatabase::SqliteDatabase(const std::string& path) : path_(path) {
  SLAM_THROW_IF_NOT(InputError, std::filesystem::is_regular_file(path))
      << path << ": database file not found";
  const int rc = sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    SLAM_THROW(InputError) << path << ": cannot open as SQLite database: " << message;
  }
}

SqliteDatabase::~SqliteDatabase() { sqlite3_close(db_); }

SqliteStatement SqliteDatabase::Prepare(const std::string& sql) const {
  sqlite3_stmt* statement = nullptr;
  const int rc = sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement, nullptr);
  SLAM_THROW_IF_NOT(InputError, rc == SQLITE_OK)
      << path_ << ": SQLite error: " << sqlite3_errmsg(db_);
  return SqliteStatement(statement, path_);
}

bool SqliteDatabase::HasTable(const std::string& table) const {
  SqliteStatement statement =
      Prepare("SELECT count(*) FROM sqlite_master WHERE type='table' AND name='" + table + "'");
  return statement.Step() && statement.Int64(0) > 0;
}

std::set<std::string> SqliteDatabase::Columns(const std::string& table) const {
  SqliteStatement statement = Prepare("PRAGMA table_info(" + table + ")");
  std::set<std::string> columns;
  while (statement.Step()) columns.insert(statement.Text(1));
  return columns;
}

}  // namespace duskmap
