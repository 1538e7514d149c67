// The sim under a flood of bus input: starts simpartner-sim in real time,
// measures its real-time factor (from its SIM_STATUS) for a quiet period,
// then while a second thread of this process sends N messages a second on
// SIM_COMMAND (by default refused commands: each costs the sim a decode,
// a look-up and a reply; --kind garbage sends undecodable datagrams), and
// how a good command sent during the flood fares. Prints one table.
//   bench/flood_bench [--rate N] [--seconds S] [--kind refused|garbage] [world.xml]
#include <lcm/lcm-cpp.hpp>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/bus_decode.h"
#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_line.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/bus_signing.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace simpartner;

struct Observed {
  std::vector<status_t> statuses;
  std::vector<command_reply_t> good_replies;
  int64_t simulation_id = -1;
  BadMessageCounter bad;
};

struct Handler {
  Observed* seen;
  void OnStatus(const lcm::ReceiveBuffer* b, const std::string& channel) {
    status_t s;
    if (DecodeFromBus(channel, b->data, UnsignedSize(b->data, b->data_size), &s, &seen->bad)) return;
    seen->statuses.push_back(s);
  }
  void OnReply(const lcm::ReceiveBuffer* b, const std::string& channel) {
    command_reply_t r;
    if (DecodeFromBus(channel, b->data, UnsignedSize(b->data, b->data_size), &r, &seen->bad)) return;
    if (r.sender == "flood_bench/good" && r.accepted) seen->good_replies.push_back(r);
  }
};

// Sim seconds per wall second between the first and the last status of a
// period, from the statuses' step counts and utimes.
double RealTimeFactor(const std::vector<status_t>& s, size_t from, size_t to, double step) {
  if (to <= from + 1) return 0;
  const double wall = (s[to - 1].utime - s[from].utime) * 1e-6;
  return wall > 0 ? (s[to - 1].step - s[from].step) * step / wall : 0;
}

void Pump(lcm::LCM* bus, double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) bus->handleTimeout(5);
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "flood_bench";
  spec.summary =
      "Runs simpartner-sim on the world (default models/worlds/flat_ground.xml), then floods\n"
      "SIM_COMMAND with bad commands from another thread and prints the sim's real-time factor\n"
      "and the good commands' replies before and during the flood.";
  spec.options = {
      simpartner::Number("rate", "N", "bad commands per second (default 100000)"),
      simpartner::Number("seconds", "S", "length of each period (default 10)"),
      simpartner::Text("kind", "refused|garbage",
                       "valid commands the sim refuses, or undecodable bytes (default refused)")
          .Choices({"refused", "garbage"}),
      simpartner::Text("lcm-url", "URL", "LCM URL (default udpm://239.255.76.67:7683?ttl=0)"),
  };
  spec.positionals = {simpartner::Positional{"world.xml", 0, 1}};
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const double rate = args.Number("rate", 100000);
  const double seconds = args.Number("seconds", 10);
  const std::string kind = args.Text("kind", "refused");
  const std::string url = args.Text("lcm-url", "udpm://239.255.76.67:7683?ttl=0");
  const std::string world = args.positional().empty()
                                ? std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml"
                                : args.positional()[0];
  const double step = 0.001;
  ChildProcess sim({std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim", "--params", "/dev/null",
                    "--environment=" + world, "--lcm-url", url, "--statusPeriod=0.5",
                    "--stepsize=0.001"},
                   "/tmp/flood_bench_sim.log");
  // A large socket buffer and queue: the test's side must not be what
  // loses the good commands' replies among the flood it also receives.
  lcm::LCM bus(url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=4194304");
  // Signed as every process signs (the user's key, or SIMPARTNER_BUS_KEY).
  std::optional<BusSigning> signing = BusSigning::FromEnvironment(
      [](const std::string& line) { std::cerr << "flood_bench: " << line << "\n"; });
  BusSigning* const signer = signing ? &*signing : nullptr;
  Observed seen;
  Handler handler{&seen};
  bus.subscribe(channels::kStatus, &Handler::OnStatus, &handler)->setQueueCapacity(1000);
  bus.subscribe(channels::kCommandReply, &Handler::OnReply, &handler)->setQueueCapacity(1000000);

  // Quiet period.
  Pump(&bus, 3.0);
  const size_t quiet_from = std::min<size_t>(seen.statuses.size(), 2);
  Pump(&bus, seconds);
  const size_t quiet_to = seen.statuses.size();

  // The flood, from its own thread and LCM instance (another "process" on
  // the bus as far as the sim can tell).
  std::atomic<bool> stop{false};
  std::atomic<int64_t> sent{0};
  std::thread flooder([&] {
    // At the lowest priority: on a 2-core machine the flooder would
    // otherwise take a core from the sim that an attacker on another
    // machine would not.
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
    lcm::LCM out(url);
    command_t junk{};
    junk.sender = "flood_bench/flood";
    junk.target = "NoSuchActuator";
    junk.action = command_t::ACTION_SET;
    junk.apply_at_step = -1;
    std::vector<uint8_t> bytes(static_cast<size_t>(junk.getEncodedSize()));
    junk.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    if (kind == "garbage") bytes[24] = 0xff;  // the sender's length: negative
    const auto start = Clock::now();
    int64_t n = 0;
    while (!stop) {
      // Sends what is due by now, in bursts, then sleeps a little.
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      const int64_t due = static_cast<int64_t>(elapsed * rate);
      while (n < due && !stop) {
        // Each signed afresh (a flood from a process with the key): met by
        // the decoder, as on an unsigned bus, not refused as a replay.
        const std::vector<uint8_t> datagram =
            signer ? signer->Sign(channels::kCommand, bytes.data(), bytes.size()) : bytes;
        out.publish(channels::kCommand, datagram.data(), static_cast<unsigned>(datagram.size()));
        ++n;
      }
      sent = n;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  const auto flood_start = Clock::now();
  Pump(&bus, 1.0);
  const size_t flood_from = seen.statuses.size();
  // Good commands during the flood, one every 100 ms.
  int good_sent = 0;
  const auto flood_end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < flood_end) {
    command_t good{};
    good.sender = "flood_bench/good";
    good.request_id = ++good_sent;
    good.target = "TurnerMotor";
    good.action = command_t::ACTION_HOLD;
    good.apply_at_step = -1;
    PublishSigned(&bus, channels::kCommand, good, signer);
    Pump(&bus, 0.1);
  }
  const size_t flood_to = seen.statuses.size();
  stop = true;
  flooder.join();
  const double flood_wall = std::chrono::duration<double>(Clock::now() - flood_start).count();
  Pump(&bus, 1.5);

  control_t quit{};
  quit.sender = "flood_bench";
  quit.action = control_t::ACTION_QUIT;
  PublishSigned(&bus, channels::kControl, quit, signer);
  sim.Wait(std::chrono::seconds(5));

  if (seen.statuses.size() < 4) {
    std::fprintf(stderr, "flood_bench: the sim published %zu statuses; see /tmp/flood_bench_sim.log\n",
                 seen.statuses.size());
    return 1;
  }
  const status_t& last = seen.statuses.back();
  std::printf("flood_bench: %s, %s messages on SIM_COMMAND\n", world.c_str(), kind.c_str());
  std::printf("| what | figure |\n|---|---|\n");
  std::printf("| real-time factor, quiet (%.0f s) | %.3f |\n", seconds,
              RealTimeFactor(seen.statuses, quiet_from, quiet_to, step));
  std::printf("| flood sent | %.0f msgs/s (%lld in %.1f s) |\n", sent / flood_wall,
              static_cast<long long>(sent.load()), flood_wall);
  std::printf("| real-time factor, during the flood | %.3f |\n",
              RealTimeFactor(seen.statuses, flood_from, flood_to, step));
  std::printf("| commands refused by the sim | %lld |\n", static_cast<long long>(last.commands_rejected));
  std::printf("| undecodable messages counted | %lld |\n", static_cast<long long>(last.bad_messages));
  std::printf("| good commands accepted during the flood | %zu of %d |\n", seen.good_replies.size(),
              good_sent);
  int warnings = 0;
  for (const status_t& s : seen.statuses)
    for (const warning_t& w : s.warnings)
      if (w.message.find("more input than the step budget") != std::string::npos) ++warnings;
  std::printf("| statuses carrying the input-budget warning | %d |\n", warnings);
  return 0;
}
