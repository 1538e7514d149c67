#pragma once

#include <string>
#include <vector>

#include "simpartner/parameters.h"

namespace simpartner::sim {

// Flags of simpartner-sim besides the parameters.
const std::vector<FlagSpec>& SimFlags();

// One-paragraph description for --help.
const char* SimSummary();

}  // namespace simpartner::sim
