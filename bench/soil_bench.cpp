// What soft soil costs against rigid ground: the first world given (by
// default gen3 on rigid flat ground) and each other (by default the same
// robot on the shipped dry sand), each stepped as
//   sim       Simulation::Step
//   sim+pub   the same, SIM_STATE filled, encoded and published by the
//             sim's sending thread (bus_sender.h), until the last is out
// in interleaved rounds, so that a machine whose speed drifts slows
// every world alike; the figures are the median round (wall time) with
// the middle half of the rounds, and each world's ratio to the first is
// the median of the rounds' ratios. "x real time" is the step size over
// the median sim+pub step.
//   bench/soil_bench [--rounds N] [--steps N] [--engine ode|mujoco]
//                    [--set MOTORS] [--lcm-url URL] [rigid.xml soil.xml ...]
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/command_line.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/bus_sender.h"
#include "simpartner/sim/simulation.h"

#include "motor_settings.h"
#include "rounds.h"

namespace {

using namespace simpartner;
using Clock = std::chrono::steady_clock;

// One world, stepped alone and stepped publishing.
struct WorldRuns {
  std::string name;
  std::unique_ptr<sim::Simulation> sim, pub;
  std::unique_ptr<sim::BusSender> sender;
  std::vector<double> sim_us, pub_us;  // per round [us per step]
  bool faulted = false;
};

double MicrosPerStep(Clock::time_point start, int steps) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count() / steps;
}

void Round(WorldRuns* w, int steps) {
  auto start = Clock::now();
  for (int n = 0; n < steps; ++n) w->faulted |= !w->sim->Step();
  w->sim_us.push_back(MicrosPerStep(start, steps));
  state_t state;
  start = Clock::now();
  for (int n = 0; n < steps; ++n) {
    w->faulted |= !w->pub->Step();
    w->pub->FillState(&state);
    w->sender->Send(channels::kState, state);
  }
  w->sender->Flush();
  w->pub_us.push_back(MicrosPerStep(start, steps));
}

// The median of the rounds' ratios a / b.
double MedianRatio(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> ratio;
  for (size_t r = 0; r < a.size() && r < b.size(); ++r) ratio.push_back(a[r] / b[r]);
  return bench::Median(ratio);
}

void Print(const WorldRuns& w, const WorldRuns& first, double stepsize) {
  const double pub = bench::Median(w.pub_us);
  std::printf("%-22s %7.1f (%5.1f-%5.1f) %7.1f (%5.1f-%5.1f) %9.1f %9.3f %9.3f%s\n",
              w.name.c_str(), bench::Median(w.sim_us), bench::Quantile(w.sim_us, 0.25),
              bench::Quantile(w.sim_us, 0.75), pub, bench::Quantile(w.pub_us, 0.25),
              bench::Quantile(w.pub_us, 0.75), stepsize * 1e6 / pub,
              MedianRatio(w.sim_us, first.sim_us), MedianRatio(w.pub_us, first.pub_us),
              w.faulted ? "  FAULTED (unstable)" : "");
}

}  // namespace

int main(int argc, char** argv) {
  CommandLineSpec spec;
  spec.program = "soil_bench";
  spec.summary =
      "Microseconds per step of a robot on rigid ground (the first world) and on soil (the\n"
      "others; default gen3 on flat_ground.xml and sand_field.xml), stepped and stepped\n"
      "publishing, in interleaved rounds; the median round, and each world's ratio to the first.";
  spec.options = {
      Integer("rounds", "N", "rounds per world (default 40)").Range(1, 1e6),
      Integer("steps", "N", "steps per round (default 1000)").Range(1, 1e9),
      Text("engine", "NAME", "physics engine (default mujoco)").Choices({"ode", "mujoco"}),
      Text("set", "MOTORS",
           "NAME=FMAX,VELOCITY[;NAME=...]: velocity motors set before the first step\n"
           "(e.g. to measure a robot driving rather than standing)"),
      Text("lcm-url", "URL", "LCM URL for sim+pub (default udpm://239.255.76.67:7667?ttl=0)"),
  };
  spec.positionals = {Positional{"world.xml", 0, kAnyCount}};
  CommandLine args;
  if (const auto done = ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const int rounds = static_cast<int>(args.Integer("rounds", 40));
  const int steps = static_cast<int>(args.Integer("steps", 1000));
  Parameters params;
  params.engine = args.Text("engine", "mujoco");
  const auto motors = bench::ReadMotorSettings(args.Text("set", ""), "soil_bench", std::cerr);
  if (!motors) return 2;
  std::vector<std::string> paths = args.positional();
  if (paths.size() < 2) {
    for (const char* w : {"flat_ground.xml", "sand_field.xml"})
      paths.push_back(std::string(SP_SOURCE_DIR) + "/models/worlds/" + w);
  }
  const std::string url = args.Text("lcm-url", "udpm://239.255.76.67:7667?ttl=0");
  lcm::LCM bus(url);
  if (!bus.good()) {
    std::cerr << "soil_bench: cannot open LCM at " << url << "\n";
    return 1;
  }
  try {
    std::vector<WorldRuns> worlds;
    bool motors_ok = true;
    for (const std::string& path : paths) {
      const model::World world = model::LoadWorldOrThrow(path);
      WorldRuns w;
      w.name = std::filesystem::path(path).filename().string();
      w.sim = bench::MakeSim(world, params, *motors, "soil_bench", std::cerr, &motors_ok);
      w.pub = bench::MakeSim(world, params, *motors, "soil_bench", std::cerr, &motors_ok);
      w.sender = std::make_unique<sim::BusSender>(&bus, nullptr);
      worlds.push_back(std::move(w));
    }
    if (!motors_ok) return 2;
    for (WorldRuns& w : worlds) {  // warm up
      Round(&w, steps / 2 + 1);
      w.sim_us.clear();
      w.pub_us.clear();
    }
    for (int r = 0; r < rounds; ++r)
      for (WorldRuns& w : worlds) Round(&w, steps);
    std::printf("engine %s, %d rounds of %d steps, interleaved (median round, wall time; in "
                "brackets the middle half of the rounds)\n",
                params.engine.c_str(), rounds, steps);
    std::printf("%-22s %21s %21s %9s %9s %9s\n", "world", "sim us", "sim+pub us", "x realtime",
                "sim/first", "pub/first");
    for (const WorldRuns& w : worlds) Print(w, worlds.front(), params.stepsize);
  } catch (const std::exception& e) {
    std::cerr << "soil_bench: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
