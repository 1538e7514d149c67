// simpartner-query: list the logged simulations, export one's poses,
// contact forces or joint states to CSV, plot them with gnuplot, and (as
// the administrator) delete simulations.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "simpartner/command_line.h"
#include "simpartner/logger/query.h"

namespace {

simpartner::CommandLineSpec QueryCommandLine() {
  using namespace simpartner;
  CommandLineSpec spec;
  spec.program = "simpartner-query";
  spec.summary =
      "Lists the logged simulations, exports one's poses, contact forces or joint states to CSV, "
      "plots them with gnuplot, and (as the administrator) deletes simulations.";
  spec.options = {
      Text("db-options", "FILE",
           "MariaDB client option file (default, when dbserver is empty: reader.cnf of the "
           "private server of simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb, "
           "then ~/.local/state/simpartner/mariadb when installed or the source tree's "
           "state/mariadb; delete, prune, storage and compress: admin.cnf there)"),
      Text("body", "NAME", "only this body (e.g. Wheel1)"),
      Text("joint", "NAME", "only this joint (e.g. Axle1)"),
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

void PrintNames(simpartner::logger::DbConnection* db, const std::string& simulation) {
  using namespace simpartner::logger;
  // Through an empty-range export request: the same resolution and errors.
  ExportRequest request;
  request.simulation = simulation;
  std::unique_ptr<sql::ResultSet> rows;
  std::string id;
  request.to = -1;
  id = std::to_string(ReadExport(db, request, [](const ExportStep&) {}));
  for (const char* table : {"Body", "`Joint`"}) {
    rows = db->Query(std::string("SELECT name, type FROM ") + table + " WHERE simulationID = " + id +
                         " ORDER BY busIndex",
                     std::string("SELECT name FROM ") + table);
    std::cout << (table[0] == 'B' ? "bodies:" : "joints:");
    while (rows->next())
      std::cout << " " << std::string(rows->getString(1)) << " (" << std::string(rows->getString(2))
                << ")";
    std::cout << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(QueryCommandLine(), {argv + 1, argv + argc}, std::cout,
                                        std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    const std::string& command = command_line.command();
    const bool admin =
        command == "delete" || command == "prune" || command == "storage" || command == "compress";
    std::vector<std::string> warnings;
    const logger::DbTarget target = logger::ResolveDbTarget(
        params, command_line.Text("db-options"),
        admin ? logger::kPrivateAdminOptions : logger::kPrivateReaderOptions, &warnings);
    for (const std::string& w : warnings) std::cerr << "simpartner-query: warning: " << w << "\n";
    std::unique_ptr<logger::DbConnection> db = logger::DbConnection::Open(target, false);
    db->UseDatabase(false);
    if (command == "list") {
      logger::ListSimulations(db.get(), std::cout);
      return 0;
    }
    if (command == "names") {
      PrintNames(db.get(), command_line.positional()[0]);
      return 0;
    }
    if (command == "compress") {
      logger::SetPageCompression(db.get(), command_line.positional()[0] == "on");
      std::cout << "page compression " << command_line.positional()[0] << " for";
      for (const std::string& t : logger::PerStepTables()) std::cout << " " << t;
      std::cout << "\n";
      return 0;
    }
    if (command == "storage") {
      std::printf("%-16s %12s %14s %14s  %s\n", "table", "rows", "bytes", "on disk", "compressed");
      for (const logger::TableStorage& t : logger::ReadTableStorage(db.get()))
        std::printf("%-16s %12llu %14llu %14llu  %s\n", t.table.c_str(),
                    static_cast<unsigned long long>(t.rows),
                    static_cast<unsigned long long>(t.logical_bytes),
                    static_cast<unsigned long long>(t.disk_bytes), t.compressed ? "yes" : "no");
      return 0;
    }
    if (admin) {
      const logger::DeleteSummary done =
          command == "delete"
              ? logger::DeleteSimulation(db.get(), command_line.positional()[0], command_line.Has("force"))
              : logger::PruneSimulations(db.get(), command_line.Integer("keep", 0));
      std::cout << "deleted " << done.simulations.size() << " simulation(s)";
      for (size_t i = 0; i < done.simulations.size(); ++i)
        std::cout << (i ? ", " : " (") << done.simulations[i] << (i + 1 == done.simulations.size() ? ")" : "");
      std::cout << " with " << done.steps << " logged steps\n";
      return 0;
    }
    const std::string out_path = command_line.Text("out");
    if (command == "plot") {
      logger::PlotRequest request;
      request.kind = logger::ParsePlotKind(command_line.positional()[0]);
      request.simulation = command_line.positional()[1];
      request.name = command_line.Text("joint", command_line.Text("body"));
      request.from = command_line.Number("from", request.from);
      request.to = command_line.Number("to", request.to);
      const Plot plot = logger::MakePlot(db.get(), request);
      if (!out_path.empty()) {
        DrawPlotPng(plot, out_path);
        std::cerr << "simpartner-query: " << plot.title << " -> " << out_path << "\n";
      } else if (std::getenv("DISPLAY") != nullptr && *std::getenv("DISPLAY") != '\0') {
        // Like a plot window of any command-line tool: the command ends when
        // the window is closed, so a script's next line sees it gone.
        std::cerr << "simpartner-query: " << plot.title
                  << " in a window; close it (or press q in it) to end\n";
        ShowPlotWindow(plot);
      } else {
        std::cerr << "simpartner-query: plot: no DISPLAY for a window; write a PNG with "
                     "-o FILE.png, or run it in a desktop session (or over ssh -X) for a window\n";
        return 2;
      }
      return 0;
    }
    logger::ExportRequest request;
    request.kind = command == "poses"    ? logger::ExportKind::kPoses
                   : command == "forces" ? logger::ExportKind::kForces
                                         : logger::ExportKind::kJoints;
    request.simulation = command_line.positional()[0];
    request.name = command_line.Text(request.kind == logger::ExportKind::kJoints ? "joint" : "body");
    request.from = command_line.Number("from", request.from);
    request.to = command_line.Number("to", request.to);
    request.every = command_line.Integer("every", 1);
    request.velocities = command_line.Has("velocities");
    request.unwrap = command_line.Has("unwrap");
    std::ofstream file;
    if (!out_path.empty()) {
      file.open(out_path);
      if (!file) {
        std::cerr << "simpartner-query: cannot write " << out_path << "\n";
        return 1;
      }
    }
    const uint64_t rows = logger::ExportCsv(db.get(), request, out_path.empty() ? std::cout : file);
    if (!out_path.empty()) std::cerr << "simpartner-query: " << rows << " rows to " << out_path << "\n";
    return 0;
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostics().Format() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simpartner-query: " << e.what() << "\n";
    return 1;
  }
}
