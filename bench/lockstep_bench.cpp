// What lock-step costs: a controller in this process (the
// client library's LockStep) against a real simpartner-sim, paused at
// start and run as fast as possible (speed 0).
//   1. The protocol alone: ticks per second and the wall time of one tick
//      (p50, p99, max) at period 1 on a world of one particle, where a
//      step costs a few microseconds: a tick is state out, answer back.
//      With --netns (root) also with the sim in one network namespace and
//      the controller in another (ttl=1, tests/support/netns.h).
//   2. WorkPartner gen3 (flat_ground.xml) with a controller sending its
//      four wheels and the Turner joint a command every tick: steps per
//      second and the multiple of real time, at period 1 and 10, for C++
//      and for Python (sim.lockstep, a child under the module's interpreter).
// Prints figures; docs/benchmarks.md keeps them.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../tests/support/netns.h"
#include "simpartner/child_process.h"
#include "simpartner/client/client.h"
#include "simpartner/client/lock_step.h"
#include "simpartner/command_line.h"

namespace simpartner {
namespace {

using Clock = std::chrono::steady_clock;
using client::Client;
using client::LockStep;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

std::string Url(int port, int ttl) {
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=" + std::to_string(ttl) +
         "&recv_buf_size=4194304";
}

std::vector<std::string> SimArgv(const std::string& world, const std::string& url) {
  return {std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim", "--params", "/dev/null",
          "--environment=" + std::string(SP_SOURCE_DIR) + "/models/worlds/" + world,
          "--startPaused=1", "--speed=0", "--lcm-url", url};
}

struct Figures {
  std::vector<double> tick_seconds;  // wall time of each Next()
  double wall = 0;
  int64_t steps = 0;
  double step_size = 0;
  int64_t resends = 0;
};

// Drives `ticks` ticks at `period`; with `commands`, the four wheels and
// the Turner joint are commanded every tick (a steering controller).
Figures Drive(const std::string& url, int64_t period, int64_t ticks, bool commands) {
  client::ClientOptions options;
  options.url = url;
  options.program = "lockstep_bench";
  options.model_timeout = 10;
  Client sim(options);
  std::vector<client::Target> wheels;
  if (commands)
    for (int w = 1; w <= 4; ++w) wheels.push_back(sim.Find("Axle" + std::to_string(w) + "Motor"));
  const std::optional<client::Target> turner =
      commands ? std::optional<client::Target>(sim.Find("TurnerMotor")) : std::nullopt;
  client::LockStepOptions loop_options;
  loop_options.period = period;
  loop_options.name = "bench";
  LockStep loop(sim, loop_options);
  Figures f;
  f.step_size = sim.catalog()->step_size();
  loop.Next();
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  for (int64_t k = 0; k < ticks; ++k) {
    if (commands) {
      const double t = static_cast<double>(k) / ticks;
      for (const client::Target& w : wheels) sim.Send(client::SetVelocity(w, {2.0 + t}));
      sim.Send(client::SetAngle(*turner, {0.2 * t}, 100, 100, 0));
    }
    loop.Next();
    const Clock::time_point now = Clock::now();
    f.tick_seconds.push_back(Seconds(now - last));
    last = now;
  }
  f.wall = Seconds(last - start);
  f.steps = ticks * period;
  f.resends = loop.resends();
  return f;
}

double Percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

void PrintTicks(const std::string& what, const Figures& f) {
  std::printf("%-44s %8.0f ticks/s  tick p50 %6.1f us  p99 %6.1f us  max %7.1f us  (%lld resent)\n",
              what.c_str(), f.tick_seconds.size() / f.wall, 1e6 * Percentile(f.tick_seconds, 0.5),
              1e6 * Percentile(f.tick_seconds, 0.99), 1e6 * Percentile(f.tick_seconds, 1.0),
              static_cast<long long>(f.resends));
}

void PrintRate(const std::string& what, double steps, double wall, double step_size) {
  std::printf("%-44s %8.0f steps/s  %6.2f x real time\n", what.c_str(), steps / wall,
              steps * step_size / wall);
}

// The protocol alone: one particle, period 1.
void Overhead(int port, int64_t ticks) {
  const std::string url = Url(port, 0);
  ChildProcess sim(SimArgv("free_fall.xml", url), "/dev/null");
  PrintTicks("free_fall, C++, period 1, loopback", Drive(url, 1, ticks, false));
}

void OverheadAcrossNamespaces(int port, int64_t ticks) {
  test_support::NamespaceLan lan("splsb", {"sim", "ctl"});
  const std::string url = Url(port, 1);
  ChildProcess sim(lan.Exec("sim", SimArgv("free_fall.xml", url)), "/dev/null");
  test_support::ScopedNetns inside(lan.Namespace("ctl"));
  PrintTicks("free_fall, C++, period 1, two namespaces", Drive(url, 1, ticks, false));
}

void Gen3Cpp(int port, int64_t period, int64_t steps, bool commands) {
  const std::string url = Url(port, 0);
  ChildProcess sim(SimArgv("flat_ground.xml", url), "/dev/null");
  const Figures f = Drive(url, period, steps / period, commands);
  PrintRate("gen3, C++, period " + std::to_string(period) + (commands ? "" : ", no commands"),
            static_cast<double>(f.steps), f.wall, f.step_size);
}

// A Python child running sim.lockstep, under the interpreter the module is
// built for (SP_PYTHON_EXECUTABLE, bench/CMakeLists.txt); it prints its
// wall time as its last line. A child that fails is reported with its exit
// status and everything it wrote.
void Gen3Python(int port, int64_t period, int64_t steps) {
  const std::string what = "gen3, Python, period " + std::to_string(period);
  if (std::string(SP_PYTHON_EXECUTABLE).empty()) {
    std::printf("%s: the Python module is not built\n", what.c_str());
    return;
  }
  const std::string url = Url(port, 0);
  ChildProcess sim(SimArgv("flat_ground.xml", url), "/dev/null");
  const std::string script =
      "import sys, time, simpartner\n"
      "sim = simpartner.Sim(sys.argv[1], timeout=10, program='lockstep_bench_py')\n"
      "period, ticks = int(sys.argv[2]), int(sys.argv[3])\n"
      "wheels = ['Axle%dMotor' % w for w in range(1, 5)]\n"
      "start = None\n"
      "for k, state in enumerate(sim.lockstep(period=period, steps=ticks + 1, name='bench')):\n"
      "    if start is None: start = time.monotonic()\n"
      "    for w in wheels: sim.set_velocity(w, [2.0 + k / ticks])\n"
      "    sim.set_angle('TurnerMotor', [0.2 * k / ticks], 100, 100, 0)\n"
      "print(time.monotonic() - start)\n";
  const std::string out = "/tmp/lockstep_bench_py." + std::to_string(::getpid());
  ChildProcess python({"/usr/bin/env", "PYTHONPATH=" + std::string(SP_BINARY_DIR) + "/python",
                       SP_PYTHON_EXECUTABLE, "-c", script, url, std::to_string(period),
                       std::to_string(steps / period)},
                      out);
  const std::optional<int> status = python.Wait(std::chrono::minutes(10));
  std::ostringstream output;
  output << std::ifstream(out).rdbuf();
  std::remove(out.c_str());
  std::string text = output.str();
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::string last = text.substr(text.rfind('\n') + 1);  // npos + 1 == 0
  char* end = nullptr;
  const double wall = std::strtod(last.c_str(), &end);
  const bool timed = !last.empty() && *end == '\0' && wall > 0;
  if (!status || *status != 0 || !timed) {
    const std::string how = !status ? "was still running after 10 minutes (killed)"
                            : *status != 0 ? "exited with status " + std::to_string(*status)
                                           : "exited with status 0 without its wall time";
    std::printf("%s: %s -c <script> %s; its output:\n%s\n", what.c_str(), SP_PYTHON_EXECUTABLE,
                how.c_str(), text.empty() ? "(none)" : text.c_str());
    return;
  }
  PrintRate(what, static_cast<double>(steps), wall, 0.001);
}

}  // namespace
}  // namespace simpartner

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLineSpec spec;
  spec.program = "lockstep_bench";
  spec.summary =
      "What lock-step costs: tick time (p50, p99) of the protocol alone, on loopback and\n"
      "(--netns, root) across two network namespaces, and gen3's steps per second with a\n"
      "C++ and a Python controller at period 1 and 10, the sim as fast as possible.";
  spec.options = {
      Integer("ticks", "N", "ticks of the protocol-alone runs (default 5000)"),
      Integer("steps", "N", "steps of each gen3 run (default 5000)"),
      Integer("port", "P", "first LCM port to use (default 7790; one per run)"),
      Switch("netns", "also across two network namespaces (needs root)"),
      Switch("no-python", "leave out the Python controller"),
  };
  CommandLine args;
  if (const auto done = ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const int64_t ticks = args.Integer("ticks", 5000), steps = args.Integer("steps", 5000);
  int port = static_cast<int>(args.Integer("port", 7790));
  try {
    Overhead(port++, ticks);
    if (args.Has("netns")) OverheadAcrossNamespaces(port++, ticks);
    Gen3Cpp(port++, 1, steps, false);
    for (int64_t period : {1, 10}) Gen3Cpp(port++, period, steps, true);
    if (!args.Has("no-python"))
      for (int64_t period : {1, 10}) Gen3Python(port++, period, steps);
  } catch (const std::exception& e) {
    std::cerr << "lockstep_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
