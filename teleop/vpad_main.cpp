// simpartner-teleop-vpad: simpartner-teleop with a virtual game controller
// driven by a script, for the process tests (not installed).
#include <iostream>

#include "simpartner/teleop/frontends.h"

int main(int argc, char** argv) {
  return simpartner::teleop::RunTeleop({argv + 1, argv + argc}, true, std::cout, std::cerr);
}
