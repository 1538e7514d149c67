#include "simpartner/logger/simulations.h"

#include <cppconn/exception.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "simpartner/edit_distance.h"

namespace simpartner::logger {
namespace {

// Whether Simulation has `column`: a database no logger of that schema
// version has opened yet lacks it (the query tool only reads).
bool SimulationHasColumn(DbConnection* db, const std::string& column) {
  return db->QueryInt("SELECT COUNT(*) FROM information_schema.COLUMNS WHERE TABLE_SCHEMA = "
                      "DATABASE() AND TABLE_NAME = 'Simulation' AND COLUMN_NAME = '" +
                          column + "'",
                      "look for Simulation." + column, 0) > 0;
}

}  // namespace

void ListSimulations(DbConnection* db, std::ostream& out) {
  // tag came with schema 7, engine with schema 8 ('ode': every simulation
  // logged before ran ODE).
  const std::string tag = SimulationHasColumn(db, "tag") ? "s.tag" : "NULL";
  const std::string engine = SimulationHasColumn(db, "engine") ? "s.engine" : "'ode'";
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT s.simulationID, s.busSimulationID, s.host, s.worldName, " + engine +
          ", s.startTime, s.endTime, "
          "(SELECT COUNT(*) FROM SimulationRow r WHERE r.simulationID = s.simulationID), "
          "(SELECT MAX(step) FROM SimulationRow r WHERE r.simulationID = s.simulationID), "
          "(SELECT COALESCE(SUM(missing), 0) FROM LogGap g WHERE g.simulationID = s.simulationID), "
          "COALESCE(s.endReason, 'open'), " + tag + " FROM Simulation s ORDER BY s.simulationID",
      "list simulations");
  char line[560];
  std::snprintf(line, sizeof line, "%-6s %-18s %-16s %-20s %-7s %-26s %-26s %10s %10s %8s  %s\n",
                "id", "bus id", "host", "world", "engine", "start (UTC)", "end (UTC)", "steps",
                "last step", "missing", "state");
  out << line;
  try {
    while (rows->next()) {
      std::snprintf(
          line, sizeof line, "%-6u %-18lld %-16s %-20s %-7s %-26s %-26s %10lld %10s %8lld  %s\n",
          rows->getUInt(1), static_cast<long long>(rows->getInt64(2)),
          std::string(rows->getString(3)).c_str(), std::string(rows->getString(4)).c_str(),
          std::string(rows->getString(5)).c_str(), std::string(rows->getString(6)).c_str(),
          rows->isNull(7) ? "-" : std::string(rows->getString(7)).c_str(),
          static_cast<long long>(rows->getInt64(8)),
          rows->isNull(9) ? "-" : std::string(rows->getString(9)).c_str(),
          static_cast<long long>(rows->getInt64(10)), std::string(rows->getString(11)).c_str());
      out << line;
      if (!rows->isNull(12)) out << "       tag: " << std::string(rows->getString(12)) << "\n";
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the list of simulations");
  }
}

uint32_t ResolveSimulation(DbConnection* db, const std::string& which) {
  if (which == "last") {
    const int64_t id = db->QueryInt("SELECT MAX(simulationID) FROM Simulation",
                                    "SELECT MAX(simulationID) FROM Simulation", -1);
    if (id < 0) throw Error("the database '" + db->target().database + "' has no simulations yet");
    return static_cast<uint32_t>(id);
  }
  if (which == "running") {
    const int64_t id =
        db->QueryInt("SELECT MAX(simulationID) FROM Simulation WHERE endTime IS NULL",
                     "SELECT MAX(simulationID) FROM Simulation (open)", -1);
    if (id < 0)
      throw Error("no simulation is running (every simulation in database '" +
                  db->target().database + "' has ended; 'last' is the newest)");
    return static_cast<uint32_t>(id);
  }
  char* end = nullptr;
  const unsigned long id = std::strtoul(which.c_str(), &end, 10);
  if (which.empty() || *end != '\0' || id == 0 || id > 0xFFFFFFFFul)
    throw Error("simulation '" + which +
                "' is not a simulationID (a positive number), 'last' or 'running'");
  if (db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE simulationID = " + std::to_string(id),
                   "SELECT FROM Simulation", 0) == 0)
    throw Error("no simulation " + which + " in database '" + db->target().database +
                "' (simpartner-query list shows them)");
  return static_cast<uint32_t>(id);
}

std::vector<std::string> PartNames(DbConnection* db, uint32_t simulation, PartKind kind) {
  const std::string table = kind == PartKind::kJoint    ? "`Joint`"
                            : kind == PartKind::kSensor ? "Sensor"
                                                        : "Body";
  std::unique_ptr<sql::ResultSet> rows =
      db->Query("SELECT name FROM " + table +
                    " WHERE simulationID = " + std::to_string(simulation) + " ORDER BY busIndex",
                "SELECT name FROM " + table);
  std::vector<std::string> names;
  try {
    while (rows->next()) names.push_back(rows->getString(1));
  } catch (const sql::SQLException&) {
    db->Rethrow("read the names of " + table);
  }
  return names;
}

void RequirePartName(const std::vector<std::string>& names, uint32_t simulation, PartKind kind,
                     const std::string& name) {
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  const char* part = kind == PartKind::kJoint    ? "joint"
                     : kind == PartKind::kSensor ? "sensor"
                                                 : "body";
  const char* parts = kind == PartKind::kJoint    ? "joints"
                      : kind == PartKind::kSensor ? "sensors"
                                                  : "bodies";
  std::string message = "simulation " + std::to_string(simulation) + " has no " + part +
                        " named '" + name + "'";
  size_t best = std::string::npos;
  std::string nearest;
  for (const std::string& n : names) {
    const size_t d = EditDistance(n, name);
    if (d < best) {
      best = d;
      nearest = n;
    }
  }
  if (!nearest.empty() && best <= std::max<size_t>(2, name.size() / 3))
    message += " (did you mean '" + nearest + "'?)";
  else if (!names.empty()) {
    message += "; its " + std::string(parts) + ":";
    for (size_t i = 0; i < names.size() && i < 40; ++i) message += (i ? ", " : " ") + names[i];
  }
  throw Error(message);
}

void RequirePartName(DbConnection* db, uint32_t simulation, PartKind kind,
                     const std::string& name) {
  RequirePartName(PartNames(db, simulation, kind), simulation, kind, name);
}

std::string SimulationEngine(DbConnection* db, uint32_t simulation) {
  if (!SimulationHasColumn(db, "engine")) return "ode";
  std::unique_ptr<sql::ResultSet> r = db->Query(
      "SELECT engine FROM Simulation WHERE simulationID = " + std::to_string(simulation),
      "SELECT engine FROM Simulation");
  try {
    if (r->next()) return r->getString(1);
  } catch (const sql::SQLException&) {
    db->Rethrow("read the engine of simulation " + std::to_string(simulation));
  }
  throw Error("no simulation " + std::to_string(simulation) + " in database '" +
              db->target().database + "'");
}

double LoggedStepTime(DbConnection* db, uint32_t simulation) {
  std::unique_ptr<sql::ResultSet> r =
      db->Query("SELECT stepSize * stateEvery * logInterval FROM Simulation WHERE simulationID = " +
                    std::to_string(simulation),
                "SELECT stepSize FROM Simulation");
  try {
    if (r->next()) return static_cast<double>(r->getDouble(1));
  } catch (const sql::SQLException&) {
    db->Rethrow("read the step size");
  }
  return 0;
}

bool HasStoredContinuousAngle(DbConnection* db, uint32_t simulation) {
  return db->QueryInt(
             "SELECT COUNT(*) FROM information_schema.COLUMNS WHERE TABLE_SCHEMA = "
             "DATABASE() AND LOWER(TABLE_NAME) = 'jointpose' AND COLUMN_NAME = "
             "'continuousAngle'",
             "look for JointPose.continuousAngle", 0) > 0 &&
         db->QueryInt(
             "SELECT p.continuousAngle IS NOT NULL FROM SimulationRow r JOIN JointPose p "
             "ON p.simulationRowID = r.simulationRowID WHERE r.simulationID = " +
                 std::to_string(simulation) + " ORDER BY r.step LIMIT 1",
             "SELECT continuousAngle FROM JointPose", 0) == 1;
}

}  // namespace simpartner::logger
