// simpartner-query's command line: an options struct and a command enum
// that dispatch into the query library (query.h). main() reads the
// command line and the parameters, then calls RunQuery.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string>

#include "simpartner/command_line.h"
#include "simpartner/parameters.h"

namespace simpartner::logger {

enum class QueryCommand {
  kList, kNames, kPoses, kForces, kJoints, kReadings, kPlot, kDelete, kPrune, kStorage, kCompress
};

struct QueryOptions {
  QueryCommand command = QueryCommand::kList;
  std::string simulation;  // SIM: a simulationID, "last" or "running"
  std::string plot_kind;   // plot's WHAT (ParsePlotKind reads it)
  std::string body;        // --body: only this body ("" = all)
  std::string joint;       // --joint: only this joint
  std::string sensor;      // --sensor: only this sensor's readings ("" = every sensor's)
  std::string out_path;    // --out: the CSV or PNG file ("" = stdout, or a plot window)
  double from = -std::numeric_limits<double>::infinity();  // --from [s]
  double to = std::numeric_limits<double>::infinity();     // --to [s]
  int64_t every = 1;        // --every Nth logged step
  bool velocities = false;  // --velocities
  bool unwrap = false;      // --unwrap
  bool force = false;       // --force: delete even an open simulation
  int64_t keep = 0;         // prune --keep N
  bool compress = false;    // compress on (true) or off
  std::string db_options;   // --db-options FILE ("" = the private server's)
};

// What simpartner-query takes on its command line.
CommandLineSpec QueryCommandLine();

// The options of a command line ParseCommandLine accepted.
QueryOptions MakeQueryOptions(const CommandLine& command_line);

// Connects to the database of params (as the administrator for delete,
// prune, storage and compress, else as the reader) and runs the command,
// writing what it reads to out and notes to err. Returns the exit status
// (2: a plot window without a display); throws Error or DbError.
int RunQuery(const QueryOptions& options, const Parameters& params, std::ostream& out,
             std::ostream& err);

}  // namespace simpartner::logger
