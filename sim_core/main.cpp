// simpartner-sim: parse flags, load validated parameters and world, run.
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <iostream>
#include <stdexcept>

#include "simpartner/bus_url.h"
#include "simpartner/model/loader.h"
#include "simpartner/parameters.h"
#include "simpartner/sim/check.h"
#include "simpartner/sim/peer_watch.h"
#include "simpartner/sim/sim_node.h"
#include "simpartner/stop_signals.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(sim::SimCommandLine(), {argv + 1, argv + argc}, std::cout,
                                        std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    model::World world = sim::LoadSimWorld(command_line, params);
    std::cout << model::DescribeWorld(world) << std::flush;
    if (command_line.Has("check")) return 0;

    // SIGINT/SIGTERM end the run like SIM_CONTROL quit (a last SIM_STATUS
    // says RUN_STOPPED, so a logger closes the simulation): they arrive as a
    // readable fd that the loop watches beside the bus.
    const int stop_fd = BlockStopSignalsIntoFd();
    if (stop_fd < 0) throw std::runtime_error("cannot create a signalfd for SIGINT/SIGTERM");

    // Every datagram on the group reaches this socket, the sim's own
    // states too: with a default buffer, a sim starved of CPU for some tens
    // of milliseconds lost the commands that came in behind them.
    lcm::LCM bus(WithReceiveBuffer(params.lcmUrl));
    if (!bus.good()) {
      std::cerr << "simpartner-sim: cannot open LCM at '" << params.lcmUrl << "'\n";
      return 1;
    }
    // Before anything is published: a second sim on a bus would apply every
    // command meant for the first.
    if (!command_line.Has("allow-other-sims")) {
      if (const auto other = sim::ProbeForOtherSimulation(&bus, std::chrono::milliseconds(300))) {
        std::cerr << "simpartner-sim: " << sim::DescribeOtherSimulation(*other, params.lcmUrl)
                  << " (or start anyway with --allow-other-sims); nothing started\n";
        return 3;
      }
    }
    sim::Simulation simulation(std::move(world), params, sim::NowMicros());
    sim::SimNode node(&simulation, &bus, stop_fd);
    std::cout << "simpartner-sim: running (step " << params.stepsize << " s, "
              << params.stepper << " stepper, speed " << params.speed << ") on "
              << params.lcmUrl << std::endl;
    sim::ReportMessageSizes(simulation, std::cout);
    // Progress lines only for a person watching; a log gets the summary.
    if (::isatty(STDOUT_FILENO)) node.SetProgressOutput(&std::cout);
    const int status = node.Run();
    std::cout << node.Summary() << std::endl;
    signalfd_siginfo received{};
    if (::read(stop_fd, &received, sizeof received) == static_cast<ssize_t>(sizeof received))
      std::cout << "simpartner-sim: stopped by " << (received.ssi_signo == SIGINT ? "SIGINT" : "SIGTERM")
                << " at step " << simulation.step() << std::endl;
    ::close(stop_fd);
    return status;
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
