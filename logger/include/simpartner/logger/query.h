// simpartner-query: what is in the database, for people and for
// spreadsheets, Octave or Python: the list of simulations, and one
// simulation's poses, contact forces or joint states as CSV (SI units,
// shortest exact numbers).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

enum class ExportKind { kPoses, kForces, kJoints };

struct ExportRequest {
  ExportKind kind = ExportKind::kPoses;
  std::string simulation = "last";  // Simulation.simulationID, or "last"
  std::string name;                 // only this body (poses, forces) or joint; "" = all
};

// A table of the simulations, newest last.
void ListSimulations(DbConnection* db, std::ostream& out);
// CSV with a header line; returns the number of data rows. Throws Error for
// an unknown simulation, DbError for the database.
uint64_t ExportCsv(DbConnection* db, const ExportRequest& request, std::ostream& out);

}  // namespace simpartner::logger
