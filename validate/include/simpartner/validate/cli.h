// simpartner-validate's command line: which experiments to run, where the
// models are, whether to write the report. main() only calls RunValidate.
#pragma once

#include <ostream>
#include <vector>

#include "simpartner/parameters.h"

namespace simpartner::validate {

const std::vector<FlagSpec>& ValidateFlags();
const char* ValidateSummary();

// Runs the selected experiments, printing one line per check to `out` and
// progress to `err`. Returns 0 when every check passed, 1 when any failed,
// 2 for a bad command line, parameters file or report directory.
int RunValidate(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace simpartner::validate
