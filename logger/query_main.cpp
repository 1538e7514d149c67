// simpartner-query: list the logged simulations, export one's poses,
// contact forces or joint states to CSV, plot them with gnuplot, and (as
// the administrator) delete simulations.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "simpartner/logger/query.h"

namespace {

const std::vector<simpartner::FlagSpec> kFlags = {
    {"db-options", true,
     "MariaDB client option file (default, when dbserver is empty: reader.cnf of the private "
     "server of simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb, then "
     "~/.local/state/simpartner/mariadb when installed or the source tree's state/mariadb; "
     "delete, prune, storage and compress: admin.cnf there)"},
    {"body", true, "poses, forces, plot: only this body (e.g. Wheel1)"},
    {"joint", true, "joints, plot: only this joint (e.g. Axle1)"},
    {"out", true, "write the CSV (or the plot's PNG) to this file; -o is the same"},
    {"from", true, "export, plot: only from this simulation time [s]"},
    {"to", true, "export, plot: only up to this simulation time [s]"},
    {"every", true, "export: every Nth logged step of the range"},
    {"velocities", false, "poses: add vx, vy, vz [m/s] (central differences of x, y, z)"},
    {"unwrap", false, "joints: continuous rotational angles (no jump at +-pi)"},
    {"keep", true, "prune: how many of the newest simulations to keep"},
    {"force", false, "delete: even a simulation that is still open"},
};

const char* kSummary =
    "Commands:\n"
    "  list                  the logged simulations\n"
    "  names SIM             its bodies and joints\n"
    "  poses SIM             position (m) and axis-angle (rad) of every body per step, CSV\n"
    "  forces SIM            contact force (N) and torque (N m) on every body per step, CSV\n"
    "  joints SIM            joint anchors, angles, rates and constraint force on body1, CSV\n"
    "  plot WHAT SIM         a PNG (-o FILE.png) or, with DISPLAY and no -o, a window\n"
    "                        (the command ends when the window is closed); WHAT:\n"
    "                        position, velocity (--body B), angle, rate, force (--joint J),\n"
    "                        wheel-forces, track (x-z from above; --body, default the chassis)\n"
    "  delete SIM            remove one simulation (administrator; not while open without --force)\n"
    "  prune --keep N        remove all but the newest N simulations (administrator)\n"
    "  storage               size of the per-step tables: rows, bytes, on disk (administrator)\n"
    "  compress on|off       InnoDB page compression of the per-step tables; rebuilds them\n"
    "                        (administrator; same columns, so every query runs unchanged)\n"
    "SIM is a simulationID from 'list', 'last' (the newest) or 'running' (the newest still open).";

double NumberFlag(const simpartner::CommandLine& command_line, const std::string& flag,
                  double fallback) {
  if (!command_line.Has(flag)) return fallback;
  const std::string text = command_line.Value(flag, "");
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw simpartner::Error("--" + flag + " '" + text + "' is not a number");
  return value;
}

int64_t CountFlag(const simpartner::CommandLine& command_line, const std::string& flag,
                  int64_t fallback) {
  if (!command_line.Has(flag)) return fallback;
  const std::string text = command_line.Value(flag, "");
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0')
    throw simpartner::Error("--" + flag + " '" + text + "' is not a whole number");
  return value;
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
  // -o FILE is --out FILE (the usual spelling for a plot's output).
  std::vector<const char*> args(argv, argv + argc);
  for (const char*& a : args)
    if (std::string(a) == "-o") a = "--out";
  try {
    const CommandLine command_line =
        ParseCommandLine(static_cast<int>(args.size()), args.data(), kFlags);
    if (command_line.Has("help") ||
        (command_line.positional.empty() && !command_line.Has("print-parameters"))) {
      std::cout << FormatUsage("simpartner-query", kSummary, kFlags, {parameter_sections::kDatabase});
      return command_line.Has("help") ? 0 : 2;
    }
    const Parameters params = LoadParameters(command_line);
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    const std::string& command = command_line.positional[0];
    const std::vector<std::string> commands = {"list",  "names",  "poses",  "forces",  "joints",
                                               "plot",  "delete", "prune",  "storage", "compress"};
    if (std::find(commands.begin(), commands.end(), command) == commands.end()) {
      std::cerr << "simpartner-query: unknown command '" << command
                << "' (list, names, poses, forces, joints, plot, delete, prune, storage, compress)\n";
      return 2;
    }
    const size_t wanted =
        command == "list" || command == "prune" || command == "storage" ? 1 : command == "plot" ? 3 : 2;
    if (command_line.positional.size() != wanted) {
      std::cerr << "simpartner-query: " << command
                << (command == "plot"   ? " needs WHAT and SIM (e.g. plot angle last --joint Axle1)"
                    : command == "compress" ? " needs on or off"
                    : wanted == 1        ? " takes no SIM"
                                         : " needs one SIM (a simulationID, 'last' or 'running')")
                << "\n";
      return 2;
    }
    if (command == "prune" && !command_line.Has("keep")) {
      std::cerr << "simpartner-query: prune needs --keep N\n";
      return 2;
    }
    if (command == "compress" && command_line.positional[1] != "on" &&
        command_line.positional[1] != "off") {
      std::cerr << "simpartner-query: compress '" << command_line.positional[1] << "': on or off\n";
      return 2;
    }
    const bool admin =
        command == "delete" || command == "prune" || command == "storage" || command == "compress";
    std::vector<std::string> warnings;
    const logger::DbTarget target = logger::ResolveDbTarget(
        params, command_line.Value("db-options", ""),
        admin ? logger::kPrivateAdminOptions : logger::kPrivateReaderOptions, &warnings);
    for (const std::string& w : warnings) std::cerr << "simpartner-query: warning: " << w << "\n";
    std::unique_ptr<logger::DbConnection> db = logger::DbConnection::Open(target, false);
    db->UseDatabase(false);
    if (command == "list") {
      logger::ListSimulations(db.get(), std::cout);
      return 0;
    }
    if (command == "names") {
      PrintNames(db.get(), command_line.positional[1]);
      return 0;
    }
    if (command == "compress") {
      logger::SetPageCompression(db.get(), command_line.positional[1] == "on");
      std::cout << "page compression " << command_line.positional[1] << " for";
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
              ? logger::DeleteSimulation(db.get(), command_line.positional[1], command_line.Has("force"))
              : logger::PruneSimulations(db.get(), CountFlag(command_line, "keep", 0));
      std::cout << "deleted " << done.simulations.size() << " simulation(s)";
      for (size_t i = 0; i < done.simulations.size(); ++i)
        std::cout << (i ? ", " : " (") << done.simulations[i] << (i + 1 == done.simulations.size() ? ")" : "");
      std::cout << " with " << done.steps << " logged steps\n";
      return 0;
    }
    const std::string out_path = command_line.Value("out", "");
    if (command == "plot") {
      logger::PlotRequest request;
      request.kind = logger::ParsePlotKind(command_line.positional[1]);
      request.simulation = command_line.positional[2];
      request.name = command_line.Value("joint", command_line.Value("body", ""));
      request.from = NumberFlag(command_line, "from", request.from);
      request.to = NumberFlag(command_line, "to", request.to);
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
    request.simulation = command_line.positional[1];
    request.name =
        command_line.Value(request.kind == logger::ExportKind::kJoints ? "joint" : "body", "");
    request.from = NumberFlag(command_line, "from", request.from);
    request.to = NumberFlag(command_line, "to", request.to);
    request.every = CountFlag(command_line, "every", 1);
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
