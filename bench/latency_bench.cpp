// One-way latency from a command published by another process to the step
// in which simpartner-sim applies it (the reply's utime is taken when the
// command is applied, just before that step). Starts simpartner-sim in real
// time on the given world, sends commands at irregular times to its first
// actuator, and prints p50 / p99 / max against the target of one step + 1 ms.
//   bench/latency_bench [--count N] [--lcm-url URL] [world.xml]
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_line.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/sender.h"
#include "simpartner/sim/sim_node.h"
#include "simpartner/bus_signing.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  simpartner::CommandLineSpec spec;
  spec.program = "latency_bench";
  spec.summary =
      "Starts simpartner-sim in real time on the world (default models/worlds/flat_ground.xml),\n"
      "sends commands at irregular times to its first actuator and prints the one-way latency\n"
      "from command to the step that applies it: p50, p99, max against one step + 1 ms.";
  spec.options = {
      simpartner::Integer("count", "N", "commands to send (default 2000)"),
      simpartner::Text("lcm-url", "URL", "LCM URL (default udpm://239.255.76.67:7681?ttl=0)"),
  };
  spec.positionals = {simpartner::Positional{"world.xml", 0, 1}};
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const int count = static_cast<int>(args.Integer("count", 2000));
  const std::string url = args.Text("lcm-url", "udpm://239.255.76.67:7681?ttl=0");
  const std::string world = args.positional().empty()
                                ? std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml"
                                : args.positional()[0];
  std::string binary = std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim";
  ChildProcess sim({binary, "--params", "/dev/null", "--environment=" + world, "--lcm-url", url},
                   "/dev/null");
  lcm::LCM bus(url);
  // Signed as every process signs (the user's key, or SIMPARTNER_BUS_KEY).
  std::optional<BusSigning> signing = BusSigning::FromEnvironment(
      [](const std::string& line) { std::cerr << "latency_bench: " << line << "\n"; });
  BusSigning* const signer = signing ? &*signing : nullptr;
  model_t model;
  bool have_model = false;
  std::map<int64_t, int64_t> sent;  // request id -> utime
  std::vector<double> latencies_ms;
  struct Handler {
    model_t* model;
    bool* have_model;
    std::map<int64_t, int64_t>* sent;
    std::vector<double>* latencies;
    void OnModel(const lcm::ReceiveBuffer*, const std::string&, const model_t* m) {
      *model = *m;
      *have_model = true;
    }
    void OnReply(const lcm::ReceiveBuffer*, const std::string&, const command_reply_t* r) {
      const auto it = sent->find(r->request_id);
      if (it != sent->end() && r->accepted) latencies->push_back((r->utime - it->second) / 1000.0);
    }
  } handler{&model, &have_model, &sent, &latencies_ms};
  bus.subscribe(channels::kModel, &Handler::OnModel, &handler);
  bus.subscribe(channels::kCommandReply, &Handler::OnReply, &handler)->setQueueCapacity(10000);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!have_model && std::chrono::steady_clock::now() < deadline) bus.handleTimeout(50);
  if (!have_model || model.num_actuators == 0) {
    std::cerr << "latency_bench: no SIM_MODEL with an actuator from the sim\n";
    return 1;
  }
  const actuator_t& target = model.actuators[0];
  std::mt19937 random(1);
  std::uniform_int_distribution<int> gap_us(2000, 9000);
  for (int k = 0; k < count; ++k) {
    command_t c{};
    c.request_id = k + 1;
    c.sender = "latency_bench";
    c.target = target.name;
    c.action = command_t::ACTION_HOLD;
    c.apply_at_step = -1;
    c.utime = WallMicros();
    sent[c.request_id] = c.utime;
    PublishSigned(&bus, channels::kCommand, c, signer);
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(gap_us(random));
    while (std::chrono::steady_clock::now() < until) bus.handleTimeout(1);
  }
  const auto drain = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (std::chrono::steady_clock::now() < drain) bus.handleTimeout(10);
  control_t quit{};
  quit.action = control_t::ACTION_QUIT;
  PublishSigned(&bus, channels::kControl, quit, signer);
  if (!sim.Wait(std::chrono::seconds(5))) std::cerr << "latency_bench: the sim did not quit\n";
  std::sort(latencies_ms.begin(), latencies_ms.end());
  if (latencies_ms.empty()) {
    std::cerr << "latency_bench: no replies\n";
    return 1;
  }
  auto pct = [&](double p) {
    return latencies_ms[std::min(latencies_ms.size() - 1,
                                 static_cast<size_t>(p * (latencies_ms.size() - 1)))];
  };
  std::printf("commands: %d sent, %zu applied; step %.3f ms\n", count, latencies_ms.size(),
              model.step_size * 1e3);
  std::printf("command -> applied latency: p50 %.3f ms, p99 %.3f ms, max %.3f ms (target p99 <= %.3f ms)\n",
              pct(0.5), pct(0.99), latencies_ms.back(), model.step_size * 1e3 + 1.0);
  return 0;
}
