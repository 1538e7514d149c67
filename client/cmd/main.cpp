// simpartner-cmd: one command to the sim from a shell (see RunCmd).
#include <iostream>

#include "simpartner/client/cmd.h"

int main(int argc, char** argv) {
  return simpartner::client::RunCmd(std::vector<std::string>(argv + 1, argv + argc), std::cout,
                                    std::cerr);
}
