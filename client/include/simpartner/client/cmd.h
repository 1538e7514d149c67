// simpartner-cmd: the bus from a shell (like `ros2 topic pub`). The whole
// program is this function, so tests run it in-process against a real sim.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"

namespace simpartner::client {

// Exit statuses of simpartner-cmd; each names one outcome.
enum CmdExit : int {
  kCmdOk = 0,          // accepted / done
  kCmdRefused = 1,     // the sim answered: not accepted (its reason is printed)
  kCmdUsage = 2,       // bad command line or values (nothing was sent)
  kCmdNoAnswer = 3,    // no sim on the bus, or no reply in time
  kCmdUnknownName = 4, // a name or port the model does not have
  kCmdRestarted = 5,   // the sim restarted while we talked to it
};

// args without the program name, e.g. {"set", "Axle1Motor", "300,1.0"}.
int RunCmd(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// What simpartner-cmd takes on its command line: a command and its
// arguments, --timeout, and the bus as the other programs read it.
CommandLineSpec CmdCommandLine();

}  // namespace simpartner::client
