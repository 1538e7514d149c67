// simpartner-query: list the logged simulations, or export one's poses,
// contact forces or joint states to CSV.
#include <fstream>
#include <iostream>

#include "simpartner/logger/query.h"

namespace {

const std::vector<simpartner::FlagSpec> kFlags = {
    {"db-options", true,
     "MariaDB client option file (default state/mariadb/reader.cnf of the private server when "
     "dbserver is empty)"},
    {"body", true, "poses, forces: only this body (e.g. Wheel1)"},
    {"joint", true, "joints: only this joint (e.g. Turner)"},
    {"out", true, "write the CSV to this file instead of standard output"},
};

const char* kSummary =
    "Commands:\n"
    "  list                  the logged simulations\n"
    "  poses SIM             position (m) and axis-angle (rad) of every body per step, CSV\n"
    "  forces SIM            contact force (N) and torque (N m) on every body per step, CSV\n"
    "  joints SIM            joint anchors, angles, rates and constraint force on body1, CSV\n"
    "SIM is a simulationID from 'list', or 'last'.";

}  // namespace

int main(int argc, char** argv) {
  using namespace simpartner;
  try {
    const CommandLine command_line = ParseCommandLine(argc, argv, kFlags);
    if (command_line.Has("help") ||
        (command_line.positional.empty() && !command_line.Has("print-parameters"))) {
      std::cout << FormatUsage("simpartner-query", kSummary, kFlags);
      return command_line.Has("help") ? 0 : 2;
    }
    const Parameters params = LoadParameters(command_line);
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    const std::string& command = command_line.positional[0];
    logger::ExportRequest request;
    if (command == "poses") request.kind = logger::ExportKind::kPoses;
    else if (command == "forces") request.kind = logger::ExportKind::kForces;
    else if (command == "joints") request.kind = logger::ExportKind::kJoints;
    else if (command != "list") {
      std::cerr << "simpartner-query: unknown command '" << command
                << "' (list, poses, forces, joints)\n";
      return 2;
    }
    if (command != "list") {
      if (command_line.positional.size() != 2) {
        std::cerr << "simpartner-query: " << command << " needs one SIM (a simulationID or 'last')\n";
        return 2;
      }
      request.simulation = command_line.positional[1];
      request.name = command_line.Value(request.kind == logger::ExportKind::kJoints ? "joint" : "body", "");
    }
    std::vector<std::string> warnings;
    const logger::DbTarget target = logger::ResolveDbTarget(
        params, command_line.Value("db-options", ""), logger::kPrivateReaderOptions, &warnings);
    for (const std::string& w : warnings) std::cerr << "simpartner-query: warning: " << w << "\n";
    std::unique_ptr<logger::DbConnection> db = logger::DbConnection::Open(target, false);
    db->UseDatabase(false);
    if (command == "list") {
      logger::ListSimulations(db.get(), std::cout);
      return 0;
    }
    const std::string out_path = command_line.Value("out", "");
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
