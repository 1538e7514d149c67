// The logger's tables (SPEC 6) as numbered migrations. The logger brings a
// database up to the newest version when it connects; the table
// SchemaVersion records which migrations ran. Table names keep the
// original's case; with lower_case_table_names=1 the original's queries
// may spell them in any case.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

struct Migration {
  int version;
  std::string description;
  std::vector<std::string> statements;  // each idempotent (IF NOT EXISTS), so a cut-short run can repeat
};

const std::vector<Migration>& Migrations();
int LatestSchemaVersion();

// Creates the database if missing and applies the missing migrations in
// order, under a server lock so two loggers do not race. Returns the
// version the database had before. Throws DbError, also when the database
// is newer than this program. `notice` hears of each migration applied.
int MigrateSchema(DbConnection* db, const std::function<void(const std::string&)>& notice);

}  // namespace simpartner::logger
