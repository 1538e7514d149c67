#include "simpartner/logger/query.h"

#include <cppconn/exception.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {
namespace {

uint32_t ResolveSimulation(DbConnection* db, const std::string& which) {
  if (which == "last") {
    const int64_t id = db->QueryInt("SELECT MAX(simulationID) FROM Simulation",
                                    "SELECT MAX(simulationID) FROM Simulation", -1);
    if (id < 0) throw Error("the database '" + db->target().database + "' has no simulations yet");
    return static_cast<uint32_t>(id);
  }
  char* end = nullptr;
  const unsigned long id = std::strtoul(which.c_str(), &end, 10);
  if (which.empty() || *end != '\0' || id == 0 || id > 0xFFFFFFFFul)
    throw Error("simulation '" + which + "' is not a simulationID (a positive number) or 'last'");
  if (db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE simulationID = " + std::to_string(id),
                   "SELECT FROM Simulation", 0) == 0)
    throw Error("no simulation " + which + " in database '" + db->target().database +
                "' (simpartner-query list shows them)");
  return static_cast<uint32_t>(id);
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += "\"\"";
    else out += c;
  }
  return out + "\"";
}

}  // namespace

void ListSimulations(DbConnection* db, std::ostream& out) {
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT s.simulationID, s.busSimulationID, s.host, s.worldName, s.startTime, s.endTime, "
      "(SELECT COUNT(*) FROM SimulationRow r WHERE r.simulationID = s.simulationID), "
      "(SELECT MAX(step) FROM SimulationRow r WHERE r.simulationID = s.simulationID), "
      "(SELECT COALESCE(SUM(missing), 0) FROM LogGap g WHERE g.simulationID = s.simulationID), "
      "COALESCE(s.endReason, 'open') "
      "FROM Simulation s ORDER BY s.simulationID",
      "list simulations");
  char line[512];
  std::snprintf(line, sizeof line, "%-6s %-18s %-16s %-20s %-26s %-26s %10s %10s %8s  %s\n", "id",
                "bus id", "host", "world", "start (UTC)", "end (UTC)", "steps", "last step",
                "missing", "state");
  out << line;
  try {
    while (rows->next()) {
      std::snprintf(line, sizeof line, "%-6u %-18lld %-16s %-20s %-26s %-26s %10lld %10s %8lld  %s\n",
                    rows->getUInt(1), static_cast<long long>(rows->getInt64(2)),
                    std::string(rows->getString(3)).c_str(), std::string(rows->getString(4)).c_str(),
                    std::string(rows->getString(5)).c_str(),
                    rows->isNull(6) ? "-" : std::string(rows->getString(6)).c_str(),
                    static_cast<long long>(rows->getInt64(7)),
                    rows->isNull(8) ? "-" : std::string(rows->getString(8)).c_str(),
                    static_cast<long long>(rows->getInt64(9)), std::string(rows->getString(10)).c_str());
      out << line;
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the list of simulations");
  }
}

uint64_t ExportCsv(DbConnection* db, const ExportRequest& request, std::ostream& out) {
  const uint32_t simulation = ResolveSimulation(db, request.simulation);
  std::string header, sql;
  int numbers = 0;
  switch (request.kind) {
    case ExportKind::kPoses:
      header = "time_s,step,body,x_m,y_m,z_m,axis_x,axis_y,axis_z,angle_rad";
      sql = "SELECT r.simulationTime, r.step, b.name, p.x, p.y, p.z, p.axisX, p.axisY, p.axisZ, "
            "p.angle FROM SimulationRow r JOIN Pose p ON p.simulationRowID = r.simulationRowID "
            "JOIN Body b ON b.bodyID = p.bodyID WHERE r.simulationID = " +
            std::to_string(simulation) +
            (request.name.empty() ? "" : " AND b.name = " + Quoted(request.name)) +
            " ORDER BY r.step, b.busIndex";
      numbers = 7;
      break;
    case ExportKind::kForces:
      header = "time_s,step,body,Fx_N,Fy_N,Fz_N,Tx_Nm,Ty_Nm,Tz_Nm";
      sql = "SELECT r.simulationTime, r.step, b.name, f.F_x, f.F_y, f.F_z, f.T_x, f.T_y, f.T_z "
            "FROM SimulationRow r JOIN ForceAndTorque f ON f.simulationRowID = r.simulationRowID "
            "JOIN Body b ON b.bodyID = f.bodyID WHERE r.simulationID = " +
            std::to_string(simulation) +
            (request.name.empty() ? "" : " AND b.name = " + Quoted(request.name)) +
            " ORDER BY r.step, b.busIndex";
      numbers = 6;
      break;
    case ExportKind::kJoints:
      header = "time_s,step,joint,anchor_x_m,anchor_y_m,anchor_z_m,angle,angle2,angle3,rate,rate2,"
               "rate3,F1x_N,F1y_N,F1z_N,T1x_Nm,T1y_Nm,T1z_Nm";
      sql = "SELECT r.simulationTime, r.step, j.name, p.anchorx, p.anchory, p.anchorz, p.angle, "
            "p.angle2, p.angle3, p.rate, p.rate2, p.rate3, p.F_x, p.F_y, p.F_z, p.T_x, p.T_y, p.T_z "
            "FROM SimulationRow r JOIN JointPose p ON p.simulationRowID = r.simulationRowID "
            "JOIN `Joint` j ON j.jointID = p.jointID WHERE r.simulationID = " +
            std::to_string(simulation) +
            (request.name.empty() ? "" : " AND j.name = " + Quoted(request.name)) +
            " ORDER BY r.step, j.busIndex";
      numbers = 15;
      break;
  }
  if (!request.name.empty()) {
    const char* table = request.kind == ExportKind::kJoints ? "`Joint`" : "Body";
    if (db->QueryInt(std::string("SELECT COUNT(*) FROM ") + table + " WHERE simulationID = " +
                         std::to_string(simulation) + " AND name = " + Quoted(request.name),
                     std::string("SELECT FROM ") + table, 0) == 0)
      throw Error(std::string("simulation ") + std::to_string(simulation) + " has no " +
                  (request.kind == ExportKind::kJoints ? "joint" : "body") + " named '" +
                  request.name + "'");
  }
  std::unique_ptr<sql::ResultSet> rows = db->QueryStreaming(sql, "export");
  out << header << "\n";
  uint64_t count = 0;
  std::string line;
  try {
    while (rows->next()) {
      line.clear();
      AppendDouble(&line, static_cast<double>(rows->getDouble(1)));
      line.push_back(',');
      AppendInt(&line, rows->getInt64(2));
      line.push_back(',');
      line += CsvField(rows->getString(3));
      for (int k = 0; k < numbers; ++k) {
        line.push_back(',');
        AppendDouble(&line, static_cast<double>(rows->getDouble(static_cast<uint32_t>(4 + k))));
      }
      line.push_back('\n');
      out << line;
      ++count;
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the export rows");
  }
  return count;
}

}  // namespace simpartner::logger
