// simpartner-sim: parse flags, load validated parameters and world, run.
#include <iostream>

#include "simpartner/model/loader.h"
#include "simpartner/sim/sim_command_line.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sim/sim_process.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(sim::SimCommandLine(), {argv + 1, argv + argc}, std::cout,
                                        std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    for (const std::string& ignored : sim::ParametersTheEngineIgnores(params))
      std::cerr << "simpartner-sim: note: engine=" << params.engine << " does not read " << ignored
                << " (ODE's only; docs/engines.md)\n";
    model::World world = sim::LoadSimWorld(command_line, params);
    std::cout << model::DescribeWorld(world) << std::flush;
    if (command_line.Has("check")) return sim::CheckMessageSizes(world, params, std::cerr);
    return sim::RunSimProcess(std::move(world), params, command_line.Has("allow-other-sims"),
                              std::cout, std::cerr);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostics().Format() << "\n"
              << "simpartner-sim: " << e.diagnostics().size() << " error"
              << (e.diagnostics().size() == 1 ? "" : "s") << "; nothing started\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simpartner-sim: " << e.what() << "\n";
    return 1;
  }
}
