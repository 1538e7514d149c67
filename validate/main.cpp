// simpartner-validate: reruns the validation experiments (SPEC 8) and
// compares each with its target; see sp_validate.
#include <iostream>

#include "simpartner/validate/cli.h"

int main(int argc, char** argv) {
  return simpartner::validate::RunValidate({argv + 1, argv + argc}, std::cout, std::cerr);
}
