// simpartner-logger's command line: its options besides the parameters, and
// the options built from both.
#pragma once

#include <string>
#include <vector>

#include "simpartner/logger/logger.h"
#include "simpartner/command_line.h"

namespace simpartner::logger {

// What simpartner-logger takes on its command line.
CommandLineSpec LoggerCommandLine();
// Throws ConfigError naming the option file or key. Warnings go to *warnings.
LoggerOptions MakeLoggerOptions(const CommandLine& command_line, const Parameters& params,
                                std::vector<std::string>* warnings);

}  // namespace simpartner::logger
