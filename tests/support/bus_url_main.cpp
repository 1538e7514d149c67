// sp_test_bus_url OFFSET: the bus URL of tests/support/bus_url.h for the
// tests that are not C++ (the Python and shell tests), so every test takes
// its bus from one place.
#include <iostream>
#include <string>

#include "bus_url.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: sp_test_bus_url OFFSET (0 to 99)\n";
    return 2;
  }
  try {
    std::cout << simpartner::test_support::BusUrl(std::stoi(argv[1])) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "sp_test_bus_url: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
