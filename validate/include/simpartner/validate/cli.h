// simpartner-validate's command line: which experiments to run, where the
// models are, whether to write the report. main() only calls RunValidate.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"

namespace simpartner::validate {

// What simpartner-validate takes on its command line.
CommandLineSpec ValidateCommandLine();

// Runs the selected experiments, printing one line per check to `out` and
// progress to `err`. Returns 0 when every check passed, 1 when any failed,
// 2 for a bad command line, parameters file or report directory.
// args: without the program name.
int RunValidate(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace simpartner::validate
