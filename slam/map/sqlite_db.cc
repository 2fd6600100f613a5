#include "slam/map/sqlite_db.h"

#include <sqlite3.h>

#include <cstring>

#include "slam/core/check.h"
#include "slam/core/checksum.h"

namespace duskmap::mapdb {

SqliteDatabase::SqliteDatabase(const std::string& path, bool read_only) : path_(path) {
  const int flags = read_only ? SQLITE_OPEN_READONLY : (SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    SLAM_THROW(InputError) << path << ": cannot open: " << message;
  }
}

SqliteDatabase::~SqliteDatabase() { sqlite3_close(db_); }

void SqliteDatabase::ThrowIfError(int rc, const std::string& what) {
  if (rc == SQLITE_OK || rc == SQLITE_ROW || rc == SQLITE_DONE) return;
  SLAM_THROW(InputError) << path_ << ": " << what << ": " << sqlite3_errmsg(db_);
}

void SqliteDatabase::Execute(const std::string& sql) {
  ThrowIfError(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr), sql.substr(0, 40));
}

SqliteStatement SqliteDatabase::Prepare(const std::string& sql) {
  sqlite3_stmt* statement = nullptr;
  ThrowIfError(sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement, nullptr),
               "preparing '" + sql.substr(0, 40) + "'");
  return SqliteStatement(this, statement);
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(statement_); }

SqliteStatement::SqliteStatement(SqliteStatement&& other) noexcept
    : db_(other.db_), statement_(other.statement_) {
  other.statement_ = nullptr;
}

void SqliteStatement::BindInt(int index, int64_t value) {
  db_->ThrowIfError(sqlite3_bind_int64(statement_, index, value), "bind");
}
void SqliteStatement::BindDouble(int index, double value) {
  db_->ThrowIfError(sqlite3_bind_double(statement_, index, value), "bind");
}
void SqliteStatement::BindText(int index, const std::string& value) {
  db_->ThrowIfError(
      sqlite3_bind_text(statement_, index, value.c_str(), -1, SQLITE_TRANSIENT), "bind");
}
void SqliteStatement::BindBlob(int index, const std::vector<uint8_t>& value) {
  // A zero-length blob is bound as an empty (non-NULL) blob.
  static const uint8_t kEmpty = 0;
  db_->ThrowIfError(sqlite3_bind_blob64(statement_, index, value.empty() ? &kEmpty : value.data(),
                                        value.size(), SQLITE_TRANSIENT),
                    "bind");
}
void SqliteStatement::BindNull(int index) {
  db_->ThrowIfError(sqlite3_bind_null(statement_, index), "bind");
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(statement_);
  db_->ThrowIfError(rc, "step");
  return rc == SQLITE_ROW;
}

void SqliteStatement::Run() {
  while (Step()) {
  }
  Reset();
}

void SqliteStatement::Reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

bool SqliteStatement::IsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}
int64_t SqliteStatement::Int(int column) const { return sqlite3_column_int64(statement_, column); }
double SqliteStatement::Double(int column) const {
  return sqlite3_column_double(statement_, column);
}
std::string SqliteStatement::Text(int column) const {
  const unsigned char* text = sqlite3_column_text(statement_, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}
std::vector<uint8_t> SqliteStatement::Blob(int column) const {
  const void* data = sqlite3_column_blob(statement_, column);
  const int bytes = sqlite3_column_bytes(statement_, column);
  std::vector<uint8_t> blob(bytes);
  if (bytes > 0) std::memcpy(blob.data(), data, bytes);
  return blob;
}

const uint8_t* SqliteStatement::BlobData(int column, size_t* bytes) const {
  const void* data = sqlite3_column_blob(statement_, column);
  *bytes = static_cast<size_t>(sqlite3_column_bytes(statement_, column));
  return static_cast<const uint8_t*>(data);
}

uint64_t SqliteStatement::RowChecksum(int num_columns) const {
  // Each value contributes its type and bytes; the row mixes them in column
  // order (FNV-style step over the values' checksums).
  uint64_t row = 0x9e3779b97f4a7c15ull;
  for (int c = 0; c < num_columns; ++c) {
    const int type = sqlite3_column_type(statement_, c);
    uint64_t value = 0;
    switch (type) {
      case SQLITE_INTEGER: {
        const int64_t v = sqlite3_column_int64(statement_, c);
        value = Checksum64(&v, sizeof(v));
        break;
      }
      case SQLITE_FLOAT: {
        const double v = sqlite3_column_double(statement_, c);
        value = Checksum64(&v, sizeof(v));
        break;
      }
      case SQLITE_TEXT: {
        const unsigned char* text = sqlite3_column_text(statement_, c);
        value = Checksum64(text, static_cast<size_t>(sqlite3_column_bytes(statement_, c)));
        break;
      }
      case SQLITE_BLOB: {
        const void* blob = sqlite3_column_blob(statement_, c);
        value = Checksum64(blob, static_cast<size_t>(sqlite3_column_bytes(statement_, c)));
        break;
      }
      default:
        break;
    }
    row = (row ^ value ^ static_cast<uint64_t>(type)) * 0x100000001b3ull;
    row ^= row >> 31;
  }
  return row;
}

}  // namespace duskmap::mapdb
