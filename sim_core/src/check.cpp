#include "simpartner/sim/check.h"

namespace simpartner::sim {

const std::vector<FlagSpec>& SimFlags() {
  static const std::vector<FlagSpec> kFlags = {
      {"check", false,
       "load and validate the parameters, the world and its robots, print a "
       "summary and exit (0 = all good)"},
      {"allow-other-sims", false,
       "start even when another simulation is heard on the bus (by default the sim "
       "asks for SIM_MODEL first and refuses to start if another sim answers)"},
  };
  return kFlags;
}

const char* SimSummary() {
  return "The SimPartner physics process: loads the parameters, the world "
         "(parameter 'environment') and its robots, steps ODE at a fixed step "
         "and serves the simulation over LCM.";
}

}  // namespace simpartner::sim
