// simpartner-batch: runs a batch of simulations (batch_cli.h).
#include <iostream>

#include "simpartner/batch/batch_cli.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(batch::BatchCommandLine(), {argv + 1, argv + argc},
                                        std::cout, std::cerr, &command_line))
    return *done;
  try {
    return batch::RunBatchProgram(command_line, std::cout, std::cerr);
  } catch (const std::exception& e) {
    std::cerr << "simpartner-batch: " << e.what() << "\n";
    return 1;
  }
}
