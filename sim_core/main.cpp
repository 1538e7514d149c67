// simpartner-sim: parse flags, load validated parameters and world, run.
#include <iostream>

#include "simpartner/model/loader.h"
#include "simpartner/parameters.h"
#include "simpartner/sim/check.h"
#include "simpartner/sim/sim_node.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  try {
    const CommandLine command_line = ParseCommandLine(argc, argv, sim::SimFlags());
    if (command_line.Has("help")) {
      std::cout << FormatUsage("simpartner-sim", sim::SimSummary(), sim::SimFlags());
      return 0;
    }
    const Parameters params = LoadParameters(command_line);
    model::World world = model::LoadWorldOrThrow(params.environment);
    std::cout << model::DescribeWorld(world) << std::flush;
    if (command_line.Has("check")) return 0;

    lcm::LCM bus(params.lcmUrl);
    if (!bus.good()) {
      std::cerr << "simpartner-sim: cannot open LCM at '" << params.lcmUrl << "'\n";
      return 1;
    }
    sim::Simulation simulation(std::move(world), params, sim::NowMicros());
    sim::SimNode node(&simulation, &bus);
    std::cout << "simpartner-sim: running (step " << params.stepsize << " s, "
              << params.stepper << " stepper, speed " << params.speed << ") on "
              << params.lcmUrl << std::endl;
    return node.Run();
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
