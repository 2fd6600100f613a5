#include "slam/map/table_checksums.h"

#include "slam/core/check.h"
#include "slam/core/checksum.h"

namespace duskmap::mapdb {
namespace {

struct ChecksummedTable {
  const char* name;
  const char* select;
  int columns;
};
constexpr ChecksummedTable kChecksummedTables[] = {{"meta", kSelectMeta, 2},
                                                   {"sessions", kSelectSessions, 3},
                                                   {"nodes", kSelectNodes, 17},
                                                   {"links", kSelectLinks, 5},
                                                   {"words", kSelectWords, 2}};

}  // namespace

std::string TableSum::Hex() const { return Checksum64Hex(&sum, sizeof(sum)); }

void WriteChecksums(SqliteDatabase& db) {
  SqliteStatement insert = db.Prepare("INSERT INTO checksums VALUES(?, ?, ?)");
  for (const ChecksummedTable& table : kChecksummedTables) {
    TableSum sum;
    SqliteStatement select = db.Prepare(table.select);
    while (select.Step()) sum.Add(select, table.columns);
    insert.BindText(1, table.name);
    insert.BindInt(2, sum.rows);
    insert.BindText(3, sum.Hex());
    insert.Run();
  }
}

StoredChecksums ReadStoredChecksums(SqliteDatabase& db) {
  SqliteStatement has = db.Prepare("SELECT count(*) FROM sqlite_master WHERE name = 'checksums'");
  SLAM_THROW_IF_NOT(InputError, has.Step() && has.Int(0) == 1)
      << db.path() << ": the map has no table checksums (damaged, or not a duskmap map)";
  StoredChecksums stored;
  SqliteStatement select = db.Prepare("SELECT name, rows, checksum FROM checksums");
  while (select.Step()) stored[select.Text(0)] = {select.Int(1), select.Text(2)};
  return stored;
}

void VerifyTable(const StoredChecksums& stored, const char* table, const TableSum& sum,
                 const std::string& path) {
  const auto it = stored.find(table);
  SLAM_THROW_IF_NOT(InputError, it != stored.end())
      << path << ": no checksum recorded for table " << table << " (damaged map; rebuild it)";
  SLAM_THROW_IF_NOT(InputError, it->second.first == sum.rows && it->second.second == sum.Hex())
      << path << ": table " << table << " fails its checksum (" << sum.rows << " rows read, "
      << it->second.first << " saved): the map is damaged; rebuild it";
}

}  // namespace duskmap::mapdb
