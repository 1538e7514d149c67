#include "simpartner/logger/logger_config.h"

#include <cmath>
#include <cstdlib>

#include "simpartner/data_paths.h"
#include "simpartner/sender.h"

namespace simpartner::logger {

CommandLineSpec LoggerCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-logger";
  spec.summary =
      "Writes every step the sim publishes (SIM_MODEL, SIM_STATE, SIM_SENSOR, SIM_COMMAND,\n"
      "SIM_COMMAND_REPLY) into a MariaDB database (parameters dbname, dbserver, log,\n"
      "logEveryStep, logInterval). Records the database cannot take yet wait in the spool\n"
      "directory and are written when it can; SIGINT or SIGTERM stops it cleanly.";
  spec.options = {
      Text("db-options", "FILE",
           "MariaDB client option file with [client] user, password and socket or host (mode "
           "0600); default when dbserver is empty: logger.cnf of the private server of "
           "simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb, then "
           "~/.local/state/simpartner/mariadb when installed or the source tree's state/mariadb"),
      Text("spool", "DIR",
           "directory for records waiting for the database (default state/logger-spool; "
           "installed: ${XDG_STATE_HOME:-~/.local/state}/simpartner/logger-spool; "
           "$SIMPARTNER_STATE/logger-spool when that is set)"),
      Text("insert", "auto|multirow|loaddata",
           "auto (default: multi-row INSERTs for small batches, LOAD DATA LOCAL for big ones), "
           "multirow or loaddata")
          .Choices({"auto", "multirow", "loaddata"}),
      Number("queue-mb", "MB", "memory queue before records spill to the spool [MB] (default 64)")
          .Above(0, 65536),
      Number("status-period", "S", "seconds between status lines (default 10)").Above(0, 86400),
      Number("drain-timeout", "S", "seconds to go on writing after SIGINT/SIGTERM (default 10)")
          .Above(0, 86400),
      Text("tag", "TEXT",
           "mark every simulation it logs with TEXT (Simulation.tag), e.g. the batch run's "
           "values; at most 1024 characters"),
      Number("sim-silence", "S",
             "seconds without SIM_STATE or SIM_STATUS after which a simulation whose sim sent no "
             "RUN_STOPPED is closed as dead; reopened if the sim is heard again (default 10)")
          .Above(0, 86400),
  };
  spec.parameters = ParameterUse{{parameter_sections::kDatabase, parameter_sections::kTransport}};
  return spec;
}

LoggerOptions MakeLoggerOptions(const CommandLine& command_line, const Parameters& params,
                                std::vector<std::string>* warnings) {
  LoggerOptions options;
  options.lcm_url = params.lcmUrl;
  options.log_interval = params.logEveryStep ? 1 : params.logInterval;
  // An installed logger keeps its spool beside the private server's files
  // (not in whatever directory it was started from).
  const DataRoot state = StateDirectory();
  if (!state.directory.empty()) options.spool_dir = state.directory + "/logger-spool";
  options.spool_dir = command_line.Text("spool", options.spool_dir);
  const std::string insert = command_line.Text("insert", "auto");
  options.insert_method = insert == "multirow"   ? InsertMethod::kMultiRowInsert
                          : insert == "loaddata" ? InsertMethod::kLoadDataLocal
                                                 : InsertMethod::kAuto;
  options.queue_bytes = static_cast<uint64_t>(command_line.Number("queue-mb", 64) * 1e6);
  options.status_period = command_line.Number("status-period", 10);
  options.drain_timeout = command_line.Number("drain-timeout", 10);
  options.sim_silence = command_line.Number("sim-silence", 10);
  options.tag = command_line.Text("tag");
  if (options.tag.size() > 1024) {
    DiagnosticList too_long;
    too_long.Add("command line", 0, "--tag",
                 "is " + std::to_string(options.tag.size()) + " characters; at most 1024");
    throw ConfigError(too_long);
  }
  options.sender = SenderName("logger");
  options.db = ResolveDbTarget(params, command_line.Text("db-options"), kPrivateLoggerOptions,
                               warnings);
  return options;
}

}  // namespace simpartner::logger
