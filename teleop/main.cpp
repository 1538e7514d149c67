// simpartner-teleop: see teleop/include/simpartner/teleop/frontends.h.
#include <iostream>

#include "simpartner/teleop/frontends.h"

int main(int argc, char** argv) {
  return simpartner::teleop::RunTeleop({argv + 1, argv + argc}, false, std::cout, std::cerr);
}
