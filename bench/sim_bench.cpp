// Microseconds per step of the physics process, next to bare ODE stepping of
// the same world in the same run, so our overhead is a ratio:
//   bare      the engine alone (PhysicsEngine::BareStep): ODE's dSpaceCollide
//             + dWorldStep/QuickStep + dJointGroupEmpty, or MuJoCo's mj_step
//   sim       Simulation::Step (commands, controllers, step, health check)
//   sim+enc   the same plus SIM_STATE filled and encoded (our part of publishing)
//   sync pub  the same plus SIM_STATE filled, encoded and published on LCM
//             on the stepping thread
//   sim+pub   the same as the sim publishes: filled and encoded, then
//             published by its sending thread (bus_sender.h); the time
//             runs until the last state is out
//   signed    sim+pub with every SIM_STATE signed (SIMPARTNER_BUS_KEY), and
//             "signing", its cost over sim+pub
// for each world given (default: the WorkPartner worlds), each stepper
// setting, as fast as possible. Also peak resident memory.
//   bench/sim_bench [--steps N] [--lcm-url URL] [--set MOTORS] [world.xml ...]
// --set NAME=FMAX,VELOCITY[;NAME=...] sets velocity motors before the
// first step of every measurement (the bare loop's motors too), e.g. to
// measure a robot driving rather than standing.
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/bus_signing.h"
#include "simpartner/channels.h"
#include "simpartner/command_line.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/bus_sender.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sim/simulation.h"

#include "motor_settings.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace simpartner;
using bench::MakeSim;
using bench::MotorSetting;

// Peak resident set size of this process [MB] (VmHWM).
double PeakRssMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0.0;
}

double MicrosPerStep(Clock::duration d, int steps) {
  return std::chrono::duration<double, std::micro>(d).count() / steps;
}

}  // namespace

namespace {

// The engine alone on the sim's built world (PhysicsEngine::BareStep):
// its own contact defaults, the motors as the set-up before left them.
double Bare(sim::PhysicsEngine& engine, int steps) {
  const auto start = Clock::now();
  for (int n = 0; n < steps; ++n) engine.BareStep();
  return MicrosPerStep(Clock::now() - start, steps);
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "sim_bench";
  spec.summary =
      "Microseconds per step of bare ODE, Simulation::Step, + SIM_STATE encoded, + published\n"
      "on LCM, per world (default: the WorkPartner worlds gen1..gen4 on flat ground) and\n"
      "stepper setting, as fast as possible; also peak resident memory.";
  spec.options = {
      simpartner::Integer("steps", "N", "steps per measurement (default 5000)"),
      simpartner::Text("lcm-url", "URL", "LCM URL for sim+pub (default udpm://239.255.76.67:7667?ttl=0)"),
      simpartner::Text("engine", "E", "the engines measured: ode, mujoco or both (default both)")
          .Choices({"ode", "mujoco", "both"}),
      simpartner::Text("set", "MOTORS",
                       "NAME=FMAX,VELOCITY[;NAME=...]: velocity motors set before the first step\n"
                       "(e.g. to measure a robot driving rather than standing)"),
  };
  spec.positionals = {simpartner::Positional{"world.xml", 0, simpartner::kAnyCount}};
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const int steps = static_cast<int>(args.Integer("steps", 5000));
  const std::string url = args.Text("lcm-url", "udpm://239.255.76.67:7667?ttl=0");
  const std::string engines = args.Text("engine", "both");
  const auto motors = bench::ReadMotorSettings(args.Text("set", ""), "sim_bench", std::cerr);
  if (!motors) return 2;
  std::vector<std::string> worlds = args.positional();
  if (worlds.empty()) {
    for (const char* w : {"gen1_flat.xml", "flat_ground_gen2.xml", "flat_ground.xml", "gen4_flat.xml"})
      worlds.push_back(std::string(SP_SOURCE_DIR) + "/models/worlds/" + w);
  }
  lcm::LCM bus(url);
  if (!bus.good()) {
    std::cerr << "sim_bench: cannot open LCM at " << url << "\n";
    return 1;
  }
  struct Setting {
    const char* name;
    const char* engine;
    const char* stepper;
    int iterations;
  };
  const Setting settings[] = {{"dWorldStep", "ode", "accurate", 20},
                              {"QuickStep 20", "ode", "quick", 20},
                              {"QuickStep 50", "ode", "quick", 50},
                              {"QuickStep 100", "ode", "quick", 100},
                              {"MuJoCo", "mujoco", "accurate", 20}};
  std::printf("%-28s %-14s %6s %10s %10s %10s %10s %10s %10s %8s %8s %9s %8s\n", "world",
              "stepper", "bodies", "bare us", "sim us", "sim+enc us", "sync pub us", "sim+pub us",
              "signed us", "sim/bare", "pub/bare", "x realtime", "signing");
  for (const std::string& path : worlds) {
    model::WorldLoadResult loaded = model::LoadWorldFile(path);
    if (!loaded.world) {
      std::cerr << loaded.diagnostics.Format() << "\n";
      return 2;
    }
    const model::FlatModel flat = model::Flatten(*loaded.world);
    for (const Setting& setting : settings) {
      if (engines != "both" && engines != setting.engine) continue;
      Parameters params;
      params.engine = setting.engine;
      params.stepper = setting.stepper;
      params.quickStepIterations = setting.iterations;
      // A world the engine cannot run (soil on MuJoCo): said, not measured.
      const std::vector<Diagnostic> lacks = sim::EngineLimits(flat, params);
      if (!lacks.empty()) {
        std::printf("%-28s %-14s not measured: %s\n",
                    std::filesystem::path(path).filename().string().c_str(),
                    setting.name, lacks.front().message.c_str());
        continue;
      }
      // The bare engine on the same built world.
      double bare_us = 0;
      {
        sim::Simulation sim(*loaded.world, params, 1);
        // The same constraint rows as the sim holding its pose: a motor
        // (velocity 0, 1000 per axis) on every actuated joint, or as --set.
        for (const model::FlatActuator& actuator : sim.flat().actuators) {
          const int joint = actuator.joint;
          for (int axis = 0; joint >= 0 && axis < sim.flat().joints[joint].num_axes; ++axis)
            sim.engine().SetMotor(joint, axis, 0.0, 1000.0);
          for (const MotorSetting& m : *motors)
            if (m.name == actuator.name && joint >= 0)
              sim.engine().SetMotor(joint, 0, m.velocity, m.fmax);
        }
        bare_us = Bare(sim.engine(), steps);
      }
      double sim_us = 0, pub_us = 0;
      bool faulted = false, motors_ok = true;
      size_t bodies = 0;
      {
        auto made = MakeSim(*loaded.world, params, *motors, "sim_bench", std::cerr, &motors_ok);
        sim::Simulation& sim = *made;
        bodies = sim.flat().bodies.size();
        const auto start = Clock::now();
        for (int n = 0; n < steps; ++n) faulted |= !sim.Step();
        sim_us = MicrosPerStep(Clock::now() - start, steps);
      }
      if (!motors_ok) return 2;  // a --set the sim refused: said
      double enc_us = 0;
      {
        auto made = MakeSim(*loaded.world, params, *motors, "sim_bench", std::cerr, &motors_ok);
        sim::Simulation& sim = *made;
        state_t state;
        std::vector<uint8_t> buffer;
        const auto start = Clock::now();
        for (int n = 0; n < steps; ++n) {
          faulted |= !sim.Step();
          sim.FillState(&state);
          buffer.resize(static_cast<size_t>(state.getEncodedSize()));
          state.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
        }
        enc_us = MicrosPerStep(Clock::now() - start, steps);
      }
      double sync_us = 0;
      {
        auto made = MakeSim(*loaded.world, params, *motors, "sim_bench", std::cerr, &motors_ok);
        sim::Simulation& sim = *made;
        state_t state;
        const auto start = Clock::now();
        for (int n = 0; n < steps; ++n) {
          faulted |= !sim.Step();
          sim.FillState(&state);
          PublishSigned(&bus, channels::kState, state, nullptr);
        }
        sync_us = MicrosPerStep(Clock::now() - start, steps);
      }
      // Published as the sim does, unsigned and signed (bus_signing.h).
      BusSigning signing(BusSigning::Key{});
      double signed_us = 0;
      for (BusSigning* signer : {static_cast<BusSigning*>(nullptr), &signing}) {
        auto made = MakeSim(*loaded.world, params, *motors, "sim_bench", std::cerr, &motors_ok);
        sim::Simulation& sim = *made;
        sim::BusSender sender(&bus, signer);
        state_t state;
        const auto start = Clock::now();
        for (int n = 0; n < steps; ++n) {
          faulted |= !sim.Step();
          sim.FillState(&state);
          sender.Send(channels::kState, state);
        }
        sender.Flush();
        (signer ? signed_us : pub_us) = MicrosPerStep(Clock::now() - start, steps);
      }
      std::string name = std::filesystem::path(path).filename().string();
      std::printf("%-28s %-14s %6zu %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f %8.3f %8.3f %9.1f"
                  " %+7.1f%%%s\n",
                  name.c_str(), setting.name, bodies, bare_us, sim_us, enc_us, sync_us, pub_us,
                  signed_us,
                  sim_us / bare_us, pub_us / bare_us, params.stepsize * 1e6 / pub_us,
                  100.0 * (signed_us - pub_us) / pub_us, faulted ? "  FAULTED (unstable)" : "");
      std::fflush(stdout);
    }
  }
  std::printf("peak resident memory: %.1f MB\n", PeakRssMb());
  return 0;
}
