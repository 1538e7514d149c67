#include "simpartner/sim/sim_process.h"

#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <ostream>
#include <stdexcept>

#include "simpartner/bus_exposure.h"
#include "simpartner/bus_url.h"
#include "simpartner/sim/peer_watch.h"
#include "simpartner/sender.h"
#include "simpartner/sim/sim_node.h"
#include "simpartner/stop_signals.h"

namespace simpartner::sim {

int RunSimProcess(model::World world, const Parameters& params, bool allow_other_sims,
                  std::ostream& out, std::ostream& err) {
  // Every message is signed and every input must be, unless
  // SIMPARTNER_BUS_KEY=none; a bad key file stops here, named.
  std::optional<BusSigning> signing = BusSigning::FromEnvironment(
      [&err](const std::string& line) { err << "simpartner-sim: " << line << std::endl; });
  BusSigning* const signer = signing ? &*signing : nullptr;
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
    err << "simpartner-sim: cannot open LCM at '" << params.lcmUrl << "'\n";
    ::close(stop_fd);
    return 1;
  }
  // Before anything is published: a second sim on a bus would apply every
  // command meant for the first.
  if (!allow_other_sims) {
    if (const auto other = ProbeForOtherSimulation(&bus, std::chrono::milliseconds(300), signer)) {
      err << "simpartner-sim: " << DescribeOtherSimulation(*other, params.lcmUrl)
          << " (or start anyway with --allow-other-sims); nothing started\n";
      ::close(stop_fd);
      return kOtherSimulationExitStatus;
    }
  }
  Simulation simulation(std::move(world), params, WallMicros());
  const MessageSizes sizes = MeasureMessages(simulation);
  if (const std::string too_large = MessagesTooLarge(sizes); !too_large.empty()) {
    err << "simpartner-sim: " << too_large << "; nothing started\n";
    ::close(stop_fd);
    return 2;
  }
  SimNode node(&simulation, &bus, stop_fd, signer);
  if (const std::string open = BusExposureWarning(params.lcmUrl, signer != nullptr); !open.empty())
    err << "simpartner-sim: warning: " << open << std::endl;
  out << "simpartner-sim: running (step " << params.stepsize << " s, " << params.stepper
      << " stepper, speed " << params.speed << ") on " << params.lcmUrl
      << (signer ? ", signed with " + signer->key_file() : std::string(", unsigned")) << std::endl;
  ReportMessageSizes(sizes, out);
  // Progress lines only for a person watching; a log gets the summary.
  if (::isatty(STDOUT_FILENO)) node.SetProgressOutput(&out);
  const int status = node.Run();
  out << node.Summary() << std::endl;
  signalfd_siginfo received{};
  if (::read(stop_fd, &received, sizeof received) == static_cast<ssize_t>(sizeof received))
    out << "simpartner-sim: stopped by " << (received.ssi_signo == SIGINT ? "SIGINT" : "SIGTERM")
        << " at step " << simulation.step() << std::endl;
  ::close(stop_fd);
  return status;
}

int CheckMessageSizes(const model::World& world, const Parameters& params, std::ostream& err) {
  const Simulation simulation(world, params, 0);
  const std::string too_large = MessagesTooLarge(MeasureMessages(simulation));
  if (too_large.empty()) return 0;
  err << "simpartner-sim: " << too_large << "\n";
  return 2;
}

}  // namespace simpartner::sim
