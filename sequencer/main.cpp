// simpartner-sequencer: plays an XML command sequence against the sim.
#include <unistd.h>

#include <iostream>
#include <string>
#include <vector>

#include "simpartner/sequencer/cli.h"
#include "simpartner/stop_signals.h"

int main(int argc, char** argv) {
  // SIGINT and SIGTERM stop the sequence the way a refusal does (the wheel
  // motors to zero, the line said) instead of leaving the robot driving:
  // they arrive as a readable fd the player looks at between commands.
  const int stop_fd = simpartner::BlockStopSignalsIntoFd();
  const std::vector<std::string> args(argv + 1, argv + argc);
  const int status = simpartner::sequencer::RunSequencer(args, std::cout, std::cerr, stop_fd);
  if (stop_fd >= 0) ::close(stop_fd);
  return status;
}
