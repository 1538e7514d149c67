// simpartner-convert: see convert/include/simpartner/convert/convert.h.
#include <iostream>

#include "simpartner/convert/convert.h"

int main(int argc, char** argv) {
  return simpartner::convert::RunConvert({argv + 1, argv + argc}, std::cout, std::cerr);
}
