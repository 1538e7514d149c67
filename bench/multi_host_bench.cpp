// States lost and one-way latency of SIM_STATE-sized messages at 1 kHz,
// host to host (two network namespaces joined by a bridge, LCM ttl=1,
// tests/support/netns.h) and on one host (sender and receiver in the same
// namespace). The receiver listens as simpartner-logger does:
// recv_buf_size=4194304 and a 100000-message subscription queue. Sender and
// receiver are threads of this process, so their utime stamps come from the
// same clock and compare directly. Needs root (ip netns); every namespace
// it makes is removed at the end. Prints figures; docs/several-machines.md.
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "../tests/support/netns.h"
#include "simpartner/channels.h"
#include "simpartner/command_line.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"
#include "simpartner/state_t.hpp"
#include "simpartner/sender.h"

namespace simpartner {
namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  double seconds = 60;
  double rate = 1000;
  int port = 7667;
  std::string world = std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml";
};

struct Figures {
  int64_t sent = 0;
  int64_t failed_sends = 0;
  int64_t received = 0;  // distinct steps
  int64_t duplicates = 0;
  double send_seconds = 0;
  std::vector<int64_t> latencies_us;
};

// A real state of the world's robot after a few steps (gen3 by default):
// the size and content the sim publishes on SIM_STATE.
state_t RealState(const std::string& world_file) {
  model::WorldLoadResult loaded = model::LoadWorldFile(world_file);
  if (!loaded.world) {
    std::fprintf(stderr, "multi_host_bench: %s\n", loaded.diagnostics.Format().c_str());
    std::exit(1);
  }
  sim::Simulation sim(*loaded.world, Parameters(), 1);
  for (int i = 0; i < 10; ++i) sim.Step();
  state_t state;
  sim.FillState(&state);
  return state;
}

class Receiver {
 public:
  explicit Receiver(int64_t expected) : seen_(static_cast<size_t>(expected) + 1, false) {}
  void OnState(const lcm::ReceiveBuffer* buffer, const std::string&) {
    const int64_t now = WallMicros();
    state_t s;
    if (s.decode(buffer->data, 0, static_cast<int>(buffer->data_size)) < 0) return;
    if (s.step < 1 || s.step >= static_cast<int64_t>(seen_.size())) return;
    if (seen_[static_cast<size_t>(s.step)]) {
      ++figures.duplicates;
      return;
    }
    seen_[static_cast<size_t>(s.step)] = true;
    ++figures.received;
    figures.latencies_us.push_back(now - s.utime);
  }
  Figures figures;

 private:
  std::vector<bool> seen_;
};

Figures Measure(const test_support::NamespaceLan& lan, const std::string& from, const std::string& to,
                const state_t& model_state, const Options& options) {
  const std::string url = "udpm://239.255.76.67:" + std::to_string(options.port) + "?ttl=1";
  const int64_t count = static_cast<int64_t>(options.seconds * options.rate);
  Receiver receiver(count);
  std::atomic<bool> ready{false};
  std::atomic<bool> done_sending{false};
  std::thread listen([&] {
    test_support::ScopedNetns inside(lan.Namespace(to));
    lcm::LCM lcm(url + "&recv_buf_size=4194304");
    lcm.subscribe(channels::kState, &Receiver::OnState, &receiver)->setQueueCapacity(100000);
    lcm.getFileno();  // the receiving socket is made now, inside `to`
    ready = true;
    while (!done_sending) lcm.handleTimeout(50);
    // What is still in the socket's buffer and on the way.
    const auto end = Clock::now() + std::chrono::milliseconds(500);
    while (Clock::now() < end) lcm.handleTimeout(50);
  });
  while (!ready) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  Figures sent;
  std::thread send([&] {
    test_support::ScopedNetns inside(lan.Namespace(from));
    lcm::LCM lcm(url);
    state_t state = model_state;
    const auto period = std::chrono::duration<double>(1.0 / options.rate);
    const auto start = Clock::now();
    for (int64_t i = 1; i <= count; ++i) {
      std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(period * (i - 1)));
      state.step = i;
      state.utime = WallMicros();
      if (lcm.publish(channels::kState, &state) != 0) ++sent.failed_sends;
      ++sent.sent;
    }
    sent.send_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  });
  send.join();
  done_sending = true;
  listen.join();
  Figures out = receiver.figures;
  out.sent = sent.sent;
  out.failed_sends = sent.failed_sends;
  out.send_seconds = sent.send_seconds;
  return out;
}

double Percentile(std::vector<int64_t> values, double p) {
  if (values.empty()) return -1;
  std::sort(values.begin(), values.end());
  const size_t at = std::min(values.size() - 1, static_cast<size_t>(p * static_cast<double>(values.size())));
  return static_cast<double>(values[at]);
}

void Print(const char* what, const Figures& f) {
  const int64_t lost = f.sent - f.received;
  std::printf(
      "%-34s sent %lld in %.2f s (%.0f/s, %lld sends failed), received %lld, lost %lld (%.4f %%), "
      "duplicates %lld; one-way latency p50 %.0f us, p99 %.0f us, max %.0f us\n",
      what, static_cast<long long>(f.sent), f.send_seconds, static_cast<double>(f.sent) / f.send_seconds,
      static_cast<long long>(f.failed_sends), static_cast<long long>(f.received),
      static_cast<long long>(lost), 100.0 * static_cast<double>(lost) / static_cast<double>(std::max<int64_t>(1, f.sent)),
      static_cast<long long>(f.duplicates), Percentile(f.latencies_us, 0.5), Percentile(f.latencies_us, 0.99),
      Percentile(f.latencies_us, 1.0));
  std::fflush(stdout);
}

int Run(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "multi_host_bench";
  spec.summary =
      "Publishes SIM_STATE messages of the world's robot (default gen3, models/worlds/flat_ground.xml)\n"
      "at HZ for S seconds from one network namespace to another over a bridge (LCM udpm ttl=1,\n"
      "port N, inside the namespaces only), then within one namespace, and prints the states lost\n"
      "and the one-way latency p50/p99. The receiver uses recv_buf_size=4194304 and a\n"
      "100000-message queue, as simpartner-logger does. Needs root.";
  spec.options = {
      simpartner::Number("seconds", "S", "how long each path is measured (default 60)"),
      simpartner::Number("rate", "HZ", "states per second (default 1000)"),
      simpartner::Integer("port", "N", "the LCM port inside the namespaces (default 7667)"),
      simpartner::Text("world", "WORLD.xml", "the world whose robot's state is sent (default models/worlds/flat_ground.xml)"),
  };
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  Options options;
  options.seconds = args.Number("seconds", options.seconds);
  options.rate = args.Number("rate", options.rate);
  options.port = static_cast<int>(args.Integer("port", options.port));
  options.world = args.Text("world", options.world);
  for (const auto& [name, value] : {std::pair<const char*, double>{"--seconds", options.seconds},
                                    {"--rate", options.rate},
                                    {"--port", static_cast<double>(options.port)}}) {
    if (!(value > 0)) {
      std::fprintf(stderr, "multi_host_bench: %s: %g is not a positive number\n", name, value);
      return 2;
    }
  }
  const state_t state = RealState(options.world);
  std::printf("multi_host_bench: SIM_STATE of %s: %d bytes (%d bodies, %d joints), %.0f Hz for %.0f s\n",
              options.world.c_str(), state.getEncodedSize(), state.num_bodies, state.num_joints,
              options.rate, options.seconds);
  try {
    test_support::NamespaceLan lan("sp_mhb", {"a", "b"});
    std::printf("namespaces %s (%s) and %s (%s), bridge in %s_sw\n", lan.Namespace("a").c_str(),
                lan.Address("a").c_str(), lan.Namespace("b").c_str(), lan.Address("b").c_str(),
                ("sp_mhb_" + std::to_string(::getpid())).c_str());
    std::fflush(stdout);
    Print("host to host (a -> b, bridge):", Measure(lan, "a", "b", state, options));
    Print("one host (a -> a):", Measure(lan, "a", "a", state, options));
  } catch (const test_support::NetnsError& e) {
    std::fprintf(stderr, "multi_host_bench: cannot build the namespaces (root needed): %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace simpartner

int main(int argc, char** argv) { return simpartner::Run(argc, argv); }
