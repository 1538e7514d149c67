// Time keeping of the real-time loop over a long run: starts simpartner-sim
// at speed 1, receives every SIM_STATE and compares the wall time at which
// each step was published (its utime, stamped by the sim right after the
// step) since the first state with the sim time elapsed. Pacing against absolute deadlines should keep the
// difference within one step plus scheduling jitter however long it runs
// (a loop that sleeps "one step" after each step drifts by its compute time
// every step instead). Prints the drift once a minute and a summary.
//   bench/drift_bench [--seconds N (600)] [--lcm-url URL] [world.xml]
#include <lcm/lcm-cpp.hpp>

#include <signal.h>

#include <algorithm>
#include <set>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_line.h"
#include "simpartner/control_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/bus_signing.h"

namespace {

// Set by SIGINT/SIGTERM so that an interrupted run still quits its sim and
// prints what it measured (the only state a signal handler may touch).
volatile sig_atomic_t g_interrupted = 0;
void OnSignal(int) { g_interrupted = 1; }

using Clock = std::chrono::steady_clock;

struct Receiver {
  bool have_first = false;
  Clock::time_point first_wall;  // receipt, for the run length
  int64_t first_utime = 0;
  double first_sim = 0;
  int64_t last_step = -1;
  int64_t gaps = 0;  // states never received (step numbers skipped)
  int64_t received = 0;
  double drift_ms = 0;  // wall - sim since the first state, latest
  std::vector<double> drifts_ms;  // every state's drift, for percentiles
  std::set<int64_t> reanchor_steps;  // the sim's "realtime" warnings: it fell behind

  void OnStatus(const lcm::ReceiveBuffer*, const std::string&, const simpartner::status_t* s) {
    for (const auto& w : s->warnings)
      if (w.source == "realtime") reanchor_steps.insert(w.step);
  }

  void OnState(const lcm::ReceiveBuffer*, const std::string&, const simpartner::state_t* s) {
    const Clock::time_point now = Clock::now();
    if (!have_first) {
      have_first = true;
      first_wall = now;
      first_utime = s->utime;
      first_sim = s->sim_time;
    }
    if (last_step >= 0 && s->step > last_step + 1) gaps += s->step - last_step - 1;
    last_step = s->step;
    ++received;
    const double wall = static_cast<double>(s->utime - first_utime) * 1e-6;
    drift_ms = (wall - (s->sim_time - first_sim)) * 1e3;
    drifts_ms.push_back(drift_ms);
  }
};

}  // namespace

int main(int argc, char** argv) {
  using namespace simpartner;
  simpartner::CommandLineSpec spec;
  spec.program = "drift_bench";
  spec.summary =
      "Runs simpartner-sim in real time on the world (default models/worlds/flat_ground.xml)\n"
      "and prints, every 60 s and at the end, how far sim time drifted from wall time and\n"
      "how many states were lost.";
  spec.options = {
      simpartner::Number("seconds", "S", "how long to run (default 600)"),
      simpartner::Text("lcm-url", "URL", "LCM URL (default udpm://239.255.76.67:7683?ttl=0&recv_buf_size=4194304)"),
  };
  spec.positionals = {simpartner::Positional{"world.xml", 0, 1}};
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  double seconds = args.Number("seconds", 600);  // then the time it ran
  const std::string url =
      args.Text("lcm-url", "udpm://239.255.76.67:7683?ttl=0&recv_buf_size=4194304");
  const std::string world = args.positional().empty()
                                ? std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml"
                                : args.positional()[0];
  lcm::LCM bus(url);
  // Signed as every process signs (the user's key, or SIMPARTNER_BUS_KEY).
  std::optional<BusSigning> signing = BusSigning::FromEnvironment(
      [](const std::string& line) { std::cerr << "drift_bench: " << line << "\n"; });
  BusSigning* const signer = signing ? &*signing : nullptr;
  if (!bus.good()) {
    std::cerr << "drift_bench: cannot open LCM at " << url << "\n";
    return 1;
  }
  Receiver receiver;
  bus.subscribe(channels::kState, &Receiver::OnState, &receiver)->setQueueCapacity(100000);
  bus.subscribe(channels::kStatus, &Receiver::OnStatus, &receiver)->setQueueCapacity(100);
  receiver.drifts_ms.reserve(static_cast<size_t>(seconds * 1100));
  ChildProcess sim({std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim", "--params",
                    "/dev/null", "--environment=" + world, "--lcm-url", url},
                   "/dev/null");
  ::signal(SIGINT, OnSignal);
  ::signal(SIGTERM, OnSignal);
  const Clock::time_point start = Clock::now();
  Clock::time_point next_report = start + std::chrono::seconds(60);
  double step_ms = 0;
  while (true) {
    bus.handleTimeout(100);
    const Clock::time_point now = Clock::now();
    if (!sim.running()) {
      std::cerr << "drift_bench: the sim ended early\n";
      return 1;
    }
    if (g_interrupted || (receiver.have_first && std::chrono::duration<double>(
                                                     now - receiver.first_wall).count() >= seconds))
      break;
    if (now >= next_report && receiver.have_first) {
      next_report += std::chrono::seconds(60);
      std::printf("t = %4.0f s  step %lld  drift %+.3f ms  lost %lld\n",
                  std::chrono::duration<double>(now - receiver.first_wall).count(),
                  static_cast<long long>(receiver.last_step), receiver.drift_ms,
                  static_cast<long long>(receiver.gaps));
      std::fflush(stdout);
    }
  }
  control_t quit{};
  quit.action = control_t::ACTION_QUIT;
  PublishSigned(&bus, channels::kControl, quit, signer);
  sim.Wait(std::chrono::seconds(5));
  if (receiver.received < 2) {
    std::cerr << "drift_bench: no states received\n";
    return 1;
  }
  seconds = std::chrono::duration<double>(Clock::now() - receiver.first_wall).count();
  step_ms = 1e3 * seconds / static_cast<double>(receiver.last_step);  // approximate
  std::vector<double> sorted = receiver.drifts_ms;
  std::sort(sorted.begin(), sorted.end());
  auto pct = [&](double p) {
    return sorted[std::min(sorted.size() - 1, static_cast<size_t>(p * (sorted.size() - 1)))];
  };
  // Median over the last 10 s against the median over the first 10 s: a
  // drifting loop grows this linearly with the run's length; jitter and
  // single stalls (other processes on the machine) do not move medians.
  const size_t window = std::min<size_t>(sorted.size() / 4, 10000);
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const auto& d = receiver.drifts_ms;
  const double head = median(std::vector<double>(d.begin(), d.begin() + static_cast<long>(window)));
  const double tail = median(std::vector<double>(d.end() - static_cast<long>(window), d.end()));
  std::printf("run %.0f s, %lld states received, %lld lost; wall per step %.4f ms; the sim fell "
              ">100 ms behind and re-anchored %zu times\n",
              seconds, static_cast<long long>(receiver.received),
              static_cast<long long>(receiver.gaps), step_ms, receiver.reanchor_steps.size());
  std::printf("wall - sim time at the end: %+.3f ms; over the run: min %+.3f p50 %+.3f p99 %+.3f "
              "max %+.3f ms\n",
              receiver.drift_ms, sorted.front(), pct(0.5), pct(0.99), sorted.back());
  std::printf("drift: median over the last %zu states %+.4f ms minus over the first %+.4f ms = "
              "%+.4f ms\n", window, tail, head, tail - head);
  return 0;
}
