// The simpartner-sim process once its world is loaded: the bus, the check
// for another simulation on it, the run and its summary. main() only reads
// the command line, the parameters and the world before this.
#pragma once

#include <iosfwd>

#include "simpartner/model/model.h"
#include "simpartner/parameters.h"

namespace simpartner::sim {

// Exit status when another simulation answers on the bus.
inline constexpr int kOtherSimulationExitStatus = 3;

// Opens the bus (params.lcmUrl); unless allow_other_sims, refuses to start
// when another simulation answers on it; runs until SIM_CONTROL quit,
// the duration, SIGINT or SIGTERM; prints the summary. Returns the exit
// status (0 done, 1 the bus cannot be opened or the run failed, 3 another
// simulation).
int RunSimProcess(model::World world, const Parameters& params, bool allow_other_sims,
                  std::ostream& out, std::ostream& err);

// For --check: builds the world as a run would and returns 2, saying why on
// err, when its messages are too large for the bus (MessagesTooLarge), else 0.
int CheckMessageSizes(const model::World& world, const Parameters& params, std::ostream& err);

}  // namespace simpartner::sim
