// The per-step tables on the server: their sizes and page compression.
#include <cppconn/exception.h>

#include <algorithm>
#include <cctype>
#include <memory>

#include "simpartner/logger/admin.h"
#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {

const std::vector<std::string>& PerStepTables() {
  static const std::vector<std::string> tables = {"SimulationRow", "Pose", "ForceAndTorque",
                                                  "JointPose", "WheelSoil"};
  return tables;
}

bool PageCompressedOption(const std::string& create_options) {
  // MariaDB 10.11 writes `page_compressed`='1' (quoted) in CREATE_OPTIONS;
  // the value may also come unquoted or as ON.
  const std::string key = "page_compressed`=";
  const size_t at = create_options.find(key);
  if (at == std::string::npos) return false;
  std::string value = create_options.substr(at + key.size());
  value = value.substr(0, value.find(' '));
  value.erase(std::remove(value.begin(), value.end(), '\''), value.end());
  std::transform(value.begin(), value.end(), value.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return value == "1" || value == "on" || value == "yes";
}

std::vector<TableStorage> ReadTableStorage(DbConnection* db) {
  std::string list;
  for (const std::string& t : PerStepTables()) list += (list.empty() ? "" : ", ") + t;
  // FOR EXPORT writes the tables' dirty pages, so the files hold what they will.
  db->Execute("FLUSH TABLES " + list + " FOR EXPORT", "FLUSH TABLES FOR EXPORT");
  db->Execute("UNLOCK TABLES", "UNLOCK TABLES");
  std::vector<TableStorage> out;
  for (const std::string& t : PerStepTables()) {
    db->Query("ANALYZE TABLE " + t, "ANALYZE TABLE " + t);
    std::unique_ptr<sql::ResultSet> r = db->Query(
        "SELECT t.TABLE_ROWS, t.DATA_LENGTH + t.INDEX_LENGTH, s.ALLOCATED_SIZE, "
        "LOWER(t.CREATE_OPTIONS) FROM information_schema.TABLES t "
        "LEFT JOIN information_schema.INNODB_SYS_TABLESPACES s "
        "ON s.NAME = CONCAT(t.TABLE_SCHEMA, '/', t.TABLE_NAME) "
        "WHERE t.TABLE_SCHEMA = DATABASE() AND LOWER(t.TABLE_NAME) = LOWER(" + Quoted(t) + ")",
        "the size of " + t);
    try {
      if (!r->next()) throw Error("database has no table " + t + " (has the logger run on it?)");
      TableStorage ts;
      ts.table = t;
      ts.rows = r->getUInt64(1);
      ts.logical_bytes = r->getUInt64(2);
      ts.disk_bytes = r->isNull(3) ? 0 : r->getUInt64(3);
      ts.compressed = PageCompressedOption(r->getString(4));
      out.push_back(ts);
    } catch (const sql::SQLException&) {
      db->Rethrow("read the size of " + t);
    }
  }
  return out;
}

void SetPageCompression(DbConnection* db, bool on) {
  for (const std::string& t : PerStepTables())
    db->Execute("ALTER TABLE " + t + " PAGE_COMPRESSED=" + (on ? "1" : "0"),
                "ALTER TABLE " + t + " PAGE_COMPRESSED (needs the administrator: the private "
                "server's admin.cnf, or --db-options)");
}

}  // namespace simpartner::logger
