#pragma once

#include <string>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/parameters.h"

namespace simpartner::sim {

// Flags of simpartner-sim besides the parameters.
const std::vector<FlagSpec>& SimFlags();

// One-paragraph description for --help.
const char* SimSummary();

// The world the sim runs: parameter 'environment' (found as data), with
// --robot / --robot-pose / --robot-add applied. Throws ConfigError or
// ModelError.
model::World LoadSimWorld(const CommandLine& command_line, const Parameters& params);

}  // namespace simpartner::sim
