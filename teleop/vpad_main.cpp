// simpartner-teleop-vpad: simpartner-teleop with a virtual game controller
// driven by text lines (docs/driving.md), for scripted teleop without a
// controller and for the process tests.
#include <iostream>

#include "simpartner/teleop/frontends.h"

int main(int argc, char** argv) {
  return simpartner::teleop::RunTeleop({argv + 1, argv + argc}, true, std::cout, std::cerr);
}
