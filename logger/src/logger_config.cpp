#include "simpartner/logger/logger_config.h"

#include "simpartner/data_paths.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>

namespace simpartner::logger {
namespace {

double PositiveNumber(const CommandLine& command_line, const std::string& flag, double fallback,
                      double max, DiagnosticList* diagnostics) {
  const std::string text = command_line.Value(flag, "");
  if (text.empty()) return fallback;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(value) || value <= 0 || value > max) {
    char range[64];
    std::snprintf(range, sizeof range, "a number above 0 and at most %g", max);
    diagnostics->Add("command line", 0, "--" + flag, "value '" + text + "' is not " + range);
    return fallback;
  }
  return value;
}

std::string HostName() {
  char name[256] = {0};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

}  // namespace

std::vector<FlagSpec> LoggerFlags() {
  return {
      {"db-options", true,
       "MariaDB client option file with [client] user, password and socket or host (mode "
       "0600); default when dbserver is empty: logger.cnf of the private server of "
       "simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb, then "
       "~/.local/state/simpartner/mariadb when installed or the source tree's state/mariadb"},
      {"spool", true,
       "directory for records waiting for the database (default state/logger-spool; installed: "
       "${XDG_STATE_HOME:-~/.local/state}/simpartner/logger-spool; $SIMPARTNER_STATE/logger-spool "
       "when that is set)"},
      {"insert", true,
       "auto (default: multi-row INSERTs for small batches, LOAD DATA LOCAL for big ones), "
       "multirow or loaddata"},
      {"queue-mb", true, "memory queue before records spill to the spool [MB] (default 64)"},
      {"status-period", true, "seconds between status lines (default 10)"},
      {"drain-timeout", true, "seconds to go on writing after SIGINT/SIGTERM (default 10)"},
      {"sim-silence", true,
       "seconds without SIM_STATE or SIM_STATUS after which a simulation whose sim sent no "
       "RUN_STOPPED is closed as dead; reopened if the sim is heard again (default 10)"},
  };
}

std::string LoggerSummary() {
  return "Writes every step the sim publishes (SIM_MODEL, SIM_STATE, SIM_SENSOR, SIM_COMMAND,\n"
         "SIM_COMMAND_REPLY) into a MariaDB database (parameters dbname, dbserver, log,\n"
         "logEveryStep, logInterval). Records the database cannot take yet wait in the spool\n"
         "directory and are written when it can; SIGINT or SIGTERM stops it cleanly.";
}

LoggerOptions MakeLoggerOptions(const CommandLine& command_line, const Parameters& params,
                                std::vector<std::string>* warnings) {
  DiagnosticList diagnostics;
  LoggerOptions options;
  options.lcm_url = params.lcmUrl;
  options.log_interval = params.logEveryStep ? 1 : params.logInterval;
  // An installed logger keeps its spool beside the private server's files
  // (not in whatever directory it was started from).
  const DataRoot state = StateDirectory();
  if (!state.directory.empty()) options.spool_dir = state.directory + "/logger-spool";
  options.spool_dir = command_line.Value("spool", options.spool_dir);
  const std::string insert = command_line.Value("insert", "auto");
  if (insert == "auto") options.insert_method = InsertMethod::kAuto;
  else if (insert == "multirow") options.insert_method = InsertMethod::kMultiRowInsert;
  else if (insert == "loaddata") options.insert_method = InsertMethod::kLoadDataLocal;
  else diagnostics.Add("command line", 0, "--insert", "value '" + insert + "' is not auto, multirow or loaddata");
  options.queue_bytes = static_cast<uint64_t>(
      PositiveNumber(command_line, "queue-mb", 64, 65536, &diagnostics) * 1e6);
  options.status_period = PositiveNumber(command_line, "status-period", 10, 86400, &diagnostics);
  options.drain_timeout = PositiveNumber(command_line, "drain-timeout", 10, 86400, &diagnostics);
  options.sim_silence = PositiveNumber(command_line, "sim-silence", 10, 86400, &diagnostics);
  options.sender = "logger@" + HostName() + ":" + std::to_string(::getpid());
  if (!diagnostics.empty()) throw ConfigError(diagnostics);
  options.db = ResolveDbTarget(params, command_line.Value("db-options", ""), kPrivateLoggerOptions,
                               warnings);
  return options;
}

}  // namespace simpartner::logger
