// simpartner-sequencer: plays an XML command sequence against the sim.
#include <iostream>
#include <string>
#include <vector>

#include "simpartner/sequencer/cli.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return simpartner::sequencer::RunSequencer(args, std::cout, std::cerr);
}
