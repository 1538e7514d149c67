// simpartner-sim's command line and the world it names.
#pragma once

#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/model/model.h"

namespace simpartner::sim {

// What simpartner-sim takes on its command line (its options and the
// parameter sections it reads).
CommandLineSpec SimCommandLine();

// The world the sim runs: parameter 'environment' (found as data), with
// --robot / --robot-pose / --robot-add applied. Throws ConfigError or
// ModelError, or DiagnosticError naming what the chosen engine (parameter
// 'engine') cannot represent.
model::World LoadSimWorld(const CommandLine& command_line, const Parameters& params);

// LoadSimWorld without the engine's check.
model::World LoadWorldWithRobot(const CommandLine& command_line, const Parameters& params);

}  // namespace simpartner::sim
