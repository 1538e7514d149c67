// simpartner-query: list the logged simulations, export one's poses,
// contact forces or joint states to CSV, plot them with gnuplot, and (as
// the administrator) delete simulations. See query_cli.h.
#include <iostream>

#include "simpartner/logger/query_cli.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(logger::QueryCommandLine(), {argv + 1, argv + argc},
                                        std::cout, std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    return logger::RunQuery(logger::MakeQueryOptions(command_line), params, std::cout, std::cerr);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostics().Format() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simpartner-query: " << e.what() << "\n";
    return 1;
  }
}
