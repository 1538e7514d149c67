// For an administrator: deleting logged simulations, and the size and
// page compression of the per-step tables.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

// What delete and prune removed.
struct DeleteSummary {
  std::vector<uint32_t> simulations;
  uint64_t steps = 0;  // SimulationRow rows
};

// Deletes one simulation (every row of every table that belongs to it) in
// one transaction. Needs DELETE (the administrator; the logger and reader
// users have none): without it, throws Error saying so and nothing is
// deleted. An open simulation is refused unless `even_if_open`.
DeleteSummary DeleteSimulation(DbConnection* db, const std::string& simulation, bool even_if_open);
// Deletes all but the newest `keep` simulations (open ones are kept and
// count among them).
DeleteSummary PruneSimulations(DbConnection* db, int64_t keep);

// The tables that get rows every logged step.
const std::vector<std::string>& PerStepTables();

// The size of one per-step table on the server.
struct TableStorage {
  std::string table;
  uint64_t rows = 0;           // InnoDB's estimate
  uint64_t logical_bytes = 0;  // data_length + index_length: pages as InnoDB counts them
  uint64_t disk_bytes = 0;     // allocated in the file system (compressed pages take less)
  bool compressed = false;     // PAGE_COMPRESSED
};

// Writes the per-step tables' dirty pages to disk and reads their sizes.
// Needs the administrator (FLUSH TABLES, information_schema.INNODB_SYS_TABLESPACES).
std::vector<TableStorage> ReadTableStorage(DbConnection* db);
// Whether information_schema.TABLES.CREATE_OPTIONS (lower case) asks for
// page compression.
bool PageCompressedOption(const std::string& create_options);

// Switches InnoDB page compression (zlib, MariaDB's PAGE_COMPRESSED) of the
// per-step tables on or off. Rebuilds each table, rows already logged
// included; a running logger waits meanwhile. The columns stay as they are,
// so every query runs unchanged. Needs the administrator (ALTER).
void SetPageCompression(DbConnection* db, bool on);

}  // namespace simpartner::logger
