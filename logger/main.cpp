// simpartner-logger: parse flags, load parameters, log the bus into the
// database until SIGINT or SIGTERM.
#include <unistd.h>

#include <iostream>

#include "simpartner/logger/logger_config.h"
#include "simpartner/stop_signals.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(logger::LoggerCommandLine(), {argv + 1, argv + argc},
                                        std::cout, std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    if (!params.log) {
      std::cout << "simpartner-logger: log=0 in the parameters: nothing to log" << std::endl;
      return 0;
    }
    std::vector<std::string> warnings;
    const logger::LoggerOptions options = logger::MakeLoggerOptions(command_line, params, &warnings);
    logger::Reporter reporter(&std::cout, "simpartner-logger");
    for (const std::string& w : warnings) reporter.Say("warning: " + w);

    // Signals arrive as a readable fd in the receive loop (blocked before any
    // thread starts, so no thread takes them asynchronously).
    const int stop_fd = BlockStopSignalsIntoFd();

    logger::Logger logger(options, &reporter);
    reporter.Say("logging " + options.lcm_url + " into database '" + options.db.database + "' on " +
                 options.db.Server() + " (" + logger::InsertMethodName(options.insert_method) +
                 ", every " + std::to_string(options.log_interval) + ". step, spool " +
                 options.spool_dir + ")");
    const int status = logger.Run(stop_fd);
    ::close(stop_fd);
    return status;
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostics().Format() << "\nsimpartner-logger: nothing started\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simpartner-logger: " << e.what() << "\n";
    return 1;
  }
}
