// simpartner-sequencer: plays an XML command sequence against the sim.
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <iostream>
#include <string>
#include <vector>

#include "simpartner/sequencer/cli.h"

int main(int argc, char** argv) {
  // SIGINT and SIGTERM stop the sequence the way a refusal does (the wheel
  // motors to zero, the line said) instead of leaving the robot driving:
  // they arrive as a readable fd the player looks at between commands.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  const int stop_fd = signalfd(-1, &stop_signals, SFD_CLOEXEC | SFD_NONBLOCK);
  const std::vector<std::string> args(argv + 1, argv + argc);
  const int status = simpartner::sequencer::RunSequencer(args, std::cout, std::cerr, stop_fd);
  if (stop_fd >= 0) ::close(stop_fd);
  return status;
}
