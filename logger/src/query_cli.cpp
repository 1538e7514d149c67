#include "simpartner/logger/query_cli.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <ostream>

#include "simpartner/logger/query.h"

namespace simpartner::logger {
namespace {

struct CommandName {
  const char* name;
  QueryCommand command;
};
constexpr CommandName kCommands[] = {
    {"list", QueryCommand::kList},       {"names", QueryCommand::kNames},
    {"poses", QueryCommand::kPoses},     {"forces", QueryCommand::kForces},
    {"joints", QueryCommand::kJoints},   {"readings", QueryCommand::kReadings},
    {"plot", QueryCommand::kPlot},
    {"delete", QueryCommand::kDelete},   {"prune", QueryCommand::kPrune},
    {"storage", QueryCommand::kStorage}, {"compress", QueryCommand::kCompress},
};

bool NeedsAdministrator(QueryCommand command) {
  return command == QueryCommand::kDelete || command == QueryCommand::kPrune ||
         command == QueryCommand::kStorage || command == QueryCommand::kCompress;
}

std::unique_ptr<DbConnection> Connect(const QueryOptions& o, const Parameters& params,
                                      std::ostream& err) {
  std::vector<std::string> warnings;
  const DbTarget target =
      ResolveDbTarget(params, o.db_options,
                      NeedsAdministrator(o.command) ? kPrivateAdminOptions : kPrivateReaderOptions,
                      &warnings);
  for (const std::string& w : warnings) err << "simpartner-query: warning: " << w << "\n";
  std::unique_ptr<DbConnection> db = DbConnection::Open(target, false);
  db->UseDatabase(false);
  return db;
}

void PrintNames(DbConnection* db, const std::string& simulation, std::ostream& out) {
  // Through an empty-range export request: the same resolution and errors.
  ExportRequest request;
  request.simulation = simulation;
  request.to = -1;
  const std::string id = std::to_string(ReadExport(db, request, [](const ExportStep&) {}));
  for (const char* table : {"Body", "`Joint`"}) {
    std::unique_ptr<sql::ResultSet> rows =
        db->Query(std::string("SELECT name, type FROM ") + table + " WHERE simulationID = " + id +
                      " ORDER BY busIndex",
                  std::string("SELECT name FROM ") + table);
    out << (table[0] == 'B' ? "bodies:" : "joints:");
    while (rows->next())
      out << " " << std::string(rows->getString(1)) << " (" << std::string(rows->getString(2)) << ")";
    out << "\n";
  }
}

// A CSV to `out`, or to the file of --out (saying how many rows went there).
int WriteCsv(const QueryOptions& o, std::ostream& out, std::ostream& err,
             const std::function<uint64_t(std::ostream&)>& write) {
  if (o.out_path.empty()) {
    write(out);
    return 0;
  }
  std::ofstream file(o.out_path);
  if (!file) {
    err << "simpartner-query: cannot write " << o.out_path << "\n";
    return 1;
  }
  const uint64_t rows = write(file);
  err << "simpartner-query: " << rows << " rows to " << o.out_path << "\n";
  return 0;
}

int RunExport(DbConnection* db, const QueryOptions& o, std::ostream& out, std::ostream& err) {
  ExportRequest request;
  request.kind = o.command == QueryCommand::kPoses    ? ExportKind::kPoses
                 : o.command == QueryCommand::kForces ? ExportKind::kForces
                                                      : ExportKind::kJoints;
  request.simulation = o.simulation;
  request.name = request.kind == ExportKind::kJoints ? o.joint : o.body;
  request.from = o.from;
  request.to = o.to;
  request.every = o.every;
  request.velocities = o.velocities;
  request.unwrap = o.unwrap;
  return WriteCsv(o, out, err, [&](std::ostream& to) { return ExportCsv(db, request, to); });
}

int RunReadings(DbConnection* db, const QueryOptions& o, std::ostream& out, std::ostream& err) {
  ReadingsRequest request;
  request.simulation = o.simulation;
  request.sensor = o.sensor;
  request.from = o.from;
  request.to = o.to;
  return WriteCsv(o, out, err, [&](std::ostream& to) { return ExportReadingsCsv(db, request, to); });
}

int RunPlot(DbConnection* db, const QueryOptions& o, std::ostream& err) {
  PlotRequest request;
  request.kind = ParsePlotKind(o.plot_kind);
  request.simulation = o.simulation;
  request.name = o.joint.empty() ? o.body : o.joint;
  request.from = o.from;
  request.to = o.to;
  const Plot plot = MakePlot(db, request);
  if (!o.out_path.empty()) {
    DrawPlotPng(plot, o.out_path);
    err << "simpartner-query: " << plot.title << " -> " << o.out_path << "\n";
    return 0;
  }
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || *display == '\0') {
    err << "simpartner-query: plot: no DISPLAY for a window; write a PNG with -o FILE.png, or run "
           "it in a desktop session (or over ssh -X) for a window\n";
    return kUsageExitStatus;
  }
  // Like a plot window of any command-line tool: the command ends when the
  // window is closed, so a script's next line sees it gone.
  err << "simpartner-query: " << plot.title << " in a window; close it (or press q in it) to end\n";
  ShowPlotWindow(plot);
  return 0;
}

void PrintDeleted(const DeleteSummary& done, std::ostream& out) {
  out << "deleted " << done.simulations.size() << " simulation(s)";
  for (size_t i = 0; i < done.simulations.size(); ++i)
    out << (i ? ", " : " (") << done.simulations[i] << (i + 1 == done.simulations.size() ? ")" : "");
  out << " with " << done.steps << " logged steps\n";
}

void PrintStorage(const std::vector<TableStorage>& tables, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line, "%-16s %12s %14s %14s  %s\n", "table", "rows", "bytes", "on disk",
                "compressed");
  out << line;
  for (const TableStorage& t : tables) {
    std::snprintf(line, sizeof line, "%-16s %12llu %14llu %14llu  %s\n", t.table.c_str(),
                  static_cast<unsigned long long>(t.rows),
                  static_cast<unsigned long long>(t.logical_bytes),
                  static_cast<unsigned long long>(t.disk_bytes), t.compressed ? "yes" : "no");
    out << line;
  }
}

}  // namespace

CommandLineSpec QueryCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-query";
  spec.summary =
      "Lists the logged simulations, exports one's poses, contact forces, joint states or sensor "
      "readings to CSV, "
      "plots them with gnuplot, and (as the administrator) deletes simulations.";
  spec.options = {
      Text("db-options", "FILE",
           "MariaDB client option file (default, when dbserver is empty: reader.cnf of the "
           "private server of simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb, "
           "then ~/.local/state/simpartner/mariadb when installed or the source tree's "
           "state/mariadb; delete, prune, storage and compress: admin.cnf there)"),
      Text("body", "NAME", "only this body (e.g. Wheel1)"),
      Text("joint", "NAME", "only this joint (e.g. Axle1)"),
      Text("sensor", "NAME", "only this sensor's readings (e.g. Imu), under its kind's names"),
      Text("out", "FILE", "write the CSV (or the plot's PNG) to this file").Short('o'),
      Number("from", "S", "only from this simulation time [s]"),
      Number("to", "S", "only up to this simulation time [s]"),
      Integer("every", "N", "every Nth logged step of the range"),
      Switch("velocities", "add vx, vy, vz [m/s] (central differences of x, y, z)"),
      Switch("unwrap", "continuous rotational angles (no jump at +-pi)"),
      Integer("keep", "N", "how many of the newest simulations to keep"),
      Switch("force", "even a simulation that is still open"),
  };
  const Positional sim{"SIM"};
  spec.commands = {
      {"list", {}, "the logged simulations"},
      {"names", {sim}, "its bodies and joints"},
      {"poses", {sim}, "position (m) and axis-angle (rad) of every body per step, CSV",
       {"body", "out", "from", "to", "every", "velocities"}},
      {"forces", {sim}, "contact force (N) and torque (N m) on every body per step, CSV",
       {"body", "out", "from", "to", "every"}},
      {"joints", {sim}, "joint anchors, angles, rates and constraint force on body1, CSV",
       {"joint", "out", "from", "to", "every", "unwrap"}},
      {"readings", {sim},
       "logged sensor readings, CSV: with --sensor one row per reading (a lidar's: per layer) "
       "and its kind's columns (ax, ay, ... for an imu); without, one row per value (sensor, "
       "kind, layer, column, value)",
       {"sensor", "out", "from", "to"}},
      {"plot", {Positional{"WHAT"}, sim},
       "a PNG (-o FILE.png) or, with DISPLAY and no -o, a window (the command ends when the "
       "window is closed); WHAT: position, velocity (--body B), angle, rate, force (--joint J), "
       "wheel-forces, track (x-z from above; --body, default the chassis)",
       {"body", "joint", "out", "from", "to"}},
      {"delete", {sim}, "remove one simulation (administrator; not while open without --force)",
       {"force"}},
      {"prune", {}, "remove all but the newest N simulations (administrator)", {"keep"}, {"keep"}},
      {"storage", {}, "size of the per-step tables: rows, bytes, on disk (administrator)"},
      {"compress", {Positional{"on|off", 1, 1, {"on", "off"}}},
       "InnoDB page compression of the per-step tables; rebuilds them (administrator; same "
       "columns, so every query runs unchanged)"},
  };
  spec.parameters = ParameterUse{{parameter_sections::kDatabase}};
  spec.epilogue =
      "SIM is a simulationID from 'list', 'last' (the newest) or 'running' (the newest still "
      "open).";
  return spec;
}

QueryOptions MakeQueryOptions(const CommandLine& command_line) {
  QueryOptions o;
  for (const CommandName& c : kCommands)
    if (command_line.command() == c.name) o.command = c.command;
  const std::vector<std::string>& words = command_line.positional();
  if (o.command == QueryCommand::kPlot) o.plot_kind = words.at(0);
  if (o.command == QueryCommand::kCompress) o.compress = words.at(0) == "on";
  else if (!words.empty()) o.simulation = words.back();
  o.body = command_line.Text("body");
  o.joint = command_line.Text("joint");
  o.sensor = command_line.Text("sensor");
  o.out_path = command_line.Text("out");
  o.from = command_line.Number("from", o.from);
  o.to = command_line.Number("to", o.to);
  o.every = command_line.Integer("every", o.every);
  o.velocities = command_line.Has("velocities");
  o.unwrap = command_line.Has("unwrap");
  o.force = command_line.Has("force");
  o.keep = command_line.Integer("keep", o.keep);
  o.db_options = command_line.Text("db-options");
  return o;
}

int RunQuery(const QueryOptions& o, const Parameters& params, std::ostream& out,
             std::ostream& err) {
  const std::unique_ptr<DbConnection> db = Connect(o, params, err);
  switch (o.command) {
    case QueryCommand::kList:
      ListSimulations(db.get(), out);
      return 0;
    case QueryCommand::kNames:
      PrintNames(db.get(), o.simulation, out);
      return 0;
    case QueryCommand::kPoses:
    case QueryCommand::kForces:
    case QueryCommand::kJoints:
      return RunExport(db.get(), o, out, err);
    case QueryCommand::kReadings:
      return RunReadings(db.get(), o, out, err);
    case QueryCommand::kPlot:
      return RunPlot(db.get(), o, err);
    case QueryCommand::kDelete:
      PrintDeleted(DeleteSimulation(db.get(), o.simulation, o.force), out);
      return 0;
    case QueryCommand::kPrune:
      PrintDeleted(PruneSimulations(db.get(), o.keep), out);
      return 0;
    case QueryCommand::kStorage:
      PrintStorage(ReadTableStorage(db.get()), out);
      return 0;
    case QueryCommand::kCompress:
      SetPageCompression(db.get(), o.compress);
      out << "page compression " << (o.compress ? "on" : "off") << " for";
      for (const std::string& t : PerStepTables()) out << " " << t;
      out << "\n";
      return 0;
  }
  return 0;
}

}  // namespace simpartner::logger
