// Deleting simulations: every row of every table that belongs to them, in
// one transaction, or nothing.
#include <cppconn/exception.h>

#include <algorithm>
#include <memory>

#include "simpartner/logger/admin.h"
#include "simpartner/logger/simulations.h"

namespace simpartner::logger {
namespace {

// The tables with a simulationID column, children first.
const char* const kTablesBySimulation[] = {"LogGap", "SensorReading", "Command", "CommandReply",
                                           "Sensor", "Actuator", "`Joint`", "Body"};

DeleteSummary DeleteIds(DbConnection* db, const std::vector<uint32_t>& ids) {
  DeleteSummary summary;
  if (ids.empty()) return summary;
  std::string list;
  for (uint32_t id : ids) list += (list.empty() ? "" : ", ") + std::to_string(id);
  try {
    db->Begin();
    summary.steps = static_cast<uint64_t>(db->QueryInt(
        "SELECT COUNT(*) FROM SimulationRow WHERE simulationID IN (" + list + ")", "count steps", 0));
    for (const char* table : {"Pose", "ForceAndTorque", "JointPose", "WheelSoil"})
      db->Execute(std::string("DELETE t FROM ") + table +
                      " t JOIN SimulationRow r ON r.simulationRowID = t.simulationRowID "
                      "WHERE r.simulationID IN (" + list + ")",
                  std::string("DELETE FROM ") + table);
    db->Execute("DELETE FROM SimulationRow WHERE simulationID IN (" + list + ")",
                "DELETE FROM SimulationRow");
    db->Execute("DELETE c FROM RobotComponent c JOIN Robot r ON r.robotID = c.robotID "
                "WHERE r.simulationID IN (" + list + ")",
                "DELETE FROM RobotComponent");
    for (const char* table : kTablesBySimulation)
      db->Execute(std::string("DELETE FROM ") + table + " WHERE simulationID IN (" + list + ")",
                  std::string("DELETE FROM ") + table);
    db->Execute("DELETE FROM Robot WHERE simulationID IN (" + list + ")", "DELETE FROM Robot");
    db->Execute("DELETE FROM Simulation WHERE simulationID IN (" + list + ")", "DELETE FROM Simulation");
    db->Commit();
  } catch (const DbError& e) {
    db->Rollback();
    // 1142: command denied to user (no DELETE privilege).
    if (e.code() == 1142)
      throw Error("deleting needs an administrator: " + e.server() + " refuses DELETE to this user (" +
                  e.cause() + "); the logger's and the reader's users have no DELETE. Use "
                  "--db-options with the administrator's option file (the private server's is "
                  "admin.cnf beside its reader.cnf, the default of delete and prune). Nothing was "
                  "deleted");
    throw;
  }
  summary.simulations = ids;
  return summary;
}

}  // namespace

DeleteSummary DeleteSimulation(DbConnection* db, const std::string& simulation, bool even_if_open) {
  if (simulation == "last" || simulation == "running")
    throw Error("delete takes a simulationID, not '" + simulation + "' (simpartner-query list shows them)");
  const uint32_t id = ResolveSimulation(db, simulation);
  if (!even_if_open &&
      db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE endTime IS NULL AND simulationID = " +
                       std::to_string(id),
                   "SELECT FROM Simulation", 0) > 0)
    throw Error("simulation " + std::to_string(id) +
                " is still open (being logged, or its logger stopped before it ended); stop it "
                "first, or give --force");
  return DeleteIds(db, {id});
}

DeleteSummary PruneSimulations(DbConnection* db, int64_t keep) {
  if (keep < 0) throw Error("prune --keep " + std::to_string(keep) + ": must be 0 or more");
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT simulationID, endTime IS NULL FROM Simulation ORDER BY simulationID DESC",
      "SELECT simulationID FROM Simulation");
  std::vector<uint32_t> doomed;
  int64_t kept = 0;
  try {
    while (rows->next()) {
      const uint32_t id = rows->getUInt(1);
      const bool open = rows->getInt(2) != 0;
      if (kept < keep || open) {
        ++kept;  // the newest `keep`, and every open one (still being logged)
        continue;
      }
      doomed.push_back(id);
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the list of simulations");
  }
  std::sort(doomed.begin(), doomed.end());
  return DeleteIds(db, doomed);
}

}  // namespace simpartner::logger
