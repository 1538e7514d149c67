// simpartner-logger's command line: its flags besides the parameters, and
// the options built from both.
#pragma once

#include <string>
#include <vector>

#include "simpartner/logger/logger.h"
#include "simpartner/parameters.h"

namespace simpartner::logger {

std::vector<FlagSpec> LoggerFlags();
std::string LoggerSummary();
// Throws ConfigError naming the flag or key. Warnings go to *warnings.
LoggerOptions MakeLoggerOptions(const CommandLine& command_line, const Parameters& params,
                                std::vector<std::string>* warnings);

}  // namespace simpartner::logger
