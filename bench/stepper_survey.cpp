// Which stepper keeps WorkPartner stable? The original had to choose between
// dWorldStep (exact, slow) and dWorldQuickStep (fast, unstable for a
// multi-legged robot in near-singular stances). For every world given
// (default: each generation on flat ground, the slippery ground and the
// heightfield test track) and every stepper setting, this runs four
// scenarios through the same Simulation a user runs:
//   hold      5 s standing in the initial pose (every actuator holds)
//   stretch   knees driven to 0.03 rad short of straight (the near-singular
//             stance), 8 s
//   drive     wheels at 1.5 rad/s, 10 s
//   stretch+drive   both, 10 s
// and prints per run: faulted (health check), the largest joint anchor
// separation (how far the joints come apart: the solver's constraint
// error), the largest speed of any body while standing still after the
// settling time, the largest vertical speed of the heaviest body while
// driving, and the distance driven. A run is STABLE when it did not fault,
// joints stayed within 5 mm and nothing moved faster than 1 mm/s while it
// should stand still (after 1 s; after 5 s when the knees were moving):
// a robot at rest that vibrates at mm/s puts that noise into every contact
// and joint force a user reads, which is what the simulator is for.
//   bench/stepper_survey [--seconds-scale S] [world.xml ...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/command_t.hpp"
#include "simpartner/model/loader.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sim/simulation.h"

namespace {

using namespace simpartner;

struct Setting {
  const char* name;
  const char* stepper;
  int iterations;
};

struct Scenario {
  const char* name;
  bool stretch;
  bool drive;
  double seconds;
  double settle;  // standing-still checks start here
};

struct Outcome {
  bool faulted = false;
  int64_t fault_step = -1;
  double max_joint_error = 0;  // [m]
  double max_still_speed = 0;  // [m/s] any body, after settling, when not driving
  double max_vertical_speed = 0;  // [m/s] heaviest body, after settling
  double distance = 0;  // [m] heaviest body, horizontal
  double wall_seconds = 0;
};

// The largest distance between a joint's anchor as its two bodies hold
// it: zero for constraints exactly satisfied.
double MaxAnchorError(const sim::PhysicsEngine& engine, size_t joints) {
  double worst = 0.0;
  for (size_t j = 0; j < joints; ++j)
    worst = std::max(worst, engine.ReadJoint(static_cast<int>(j)).anchor_error);
  return worst;
}

command_t Command(const std::string& target, std::vector<double> values) {
  command_t c{};
  c.target = target;
  c.action = command_t::ACTION_SET;
  c.apply_at_step = -1;
  c.num_values = static_cast<int32_t>(values.size());
  c.values = std::move(values);
  return c;
}

Outcome Run(const model::World& world, const Parameters& params, const Scenario& scenario) {
  sim::Simulation sim(world, params, 1);
  const auto& flat = sim.flat();
  // The body that carries the robot: the heaviest one.
  int chassis = 0;
  for (size_t b = 0; b < flat.bodies.size(); ++b)
    if (flat.bodies[b].source->mass > flat.bodies[static_cast<size_t>(chassis)].source->mass)
      chassis = static_cast<int>(b);
  auto submit = [&](const std::string& target, std::vector<double> values) {
    if (flat.FindActuator("", target) < 0) return;  // generation without it
    if (auto reply = sim.Submit(Command(target, std::move(values)))) {
      std::cerr << "stepper_survey: " << target << " refused: " << reply->reason << "\n";
    }
  };
  if (scenario.stretch) {
    // -1.287 / +1.287 rad straightens a front / rear leg (robot files).
    for (const char* knee : {"Knee1Motor", "Knee2Motor"}) submit(knee, {1000, -1.257, 2, 0, 0});
    for (const char* knee : {"Knee3Motor", "Knee4Motor"}) submit(knee, {1000, 1.257, 2, 0, 0});
  }
  if (scenario.drive) {
    for (const char* axle : {"Axle1Motor", "Axle2Motor", "Axle3Motor", "Axle4Motor"})
      submit(axle, {1000, 1.5});
  }
  const auto start_pose = sim.engine().ReadBody(chassis).position;
  Outcome out;
  const auto t0 = std::chrono::steady_clock::now();
  const int64_t steps = static_cast<int64_t>(std::llround(scenario.seconds / params.stepsize));
  for (int64_t n = 0; n < steps; ++n) {
    if (!sim.Step()) {
      out.faulted = true;
      out.fault_step = sim.step();
      break;
    }
    out.max_joint_error =
        std::max(out.max_joint_error, MaxAnchorError(sim.engine(), flat.joints.size()));
    if (sim.time() < scenario.settle) continue;
    const auto chassis_state = sim.engine().ReadBody(chassis);
    // y is up in the WorkPartner files.
    out.max_vertical_speed =
        std::max(out.max_vertical_speed, std::abs(chassis_state.linear_velocity.y()));
    if (!scenario.drive) {
      for (size_t b = 0; b < flat.bodies.size(); ++b)
        out.max_still_speed = std::max(
            out.max_still_speed, sim.engine().ReadBody(static_cast<int>(b)).linear_velocity.norm());
    }
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto end = sim.engine().ReadBody(chassis).position;
  out.distance = std::hypot(end.x() - start_pose.x(), end.z() - start_pose.z());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "stepper_survey";
  spec.summary =
      "Which stepper keeps WorkPartner stable: for every world (default: each generation on\n"
      "flat ground, the slippery ground, the test track) and stepper setting, runs hold,\n"
      "stretch, drive and stretch+drive and prints STABLE/UNSTABLE with the joint error,\n"
      "still and vertical speeds, distance and wall time.";
  spec.options = {
      simpartner::Number("seconds-scale", "S", "multiplies every scenario's length (default 1)"),
  };
  spec.positionals = {simpartner::Positional{"world.xml", 0, simpartner::kAnyCount}};
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const double scale = args.Number("seconds-scale", 1.0);
  std::vector<std::string> worlds = args.positional();
  if (worlds.empty()) {
    for (const char* w : {"gen1_flat.xml", "flat_ground_gen2.xml", "flat_ground.xml",
                          "gen4_flat.xml", "slippery_ground.xml", "test_track.xml"})
      worlds.push_back(std::string(SP_SOURCE_DIR) + "/models/worlds/" + w);
  }
  const Setting settings[] = {{"dWorldStep", "accurate", 0},  {"QuickStep 10", "quick", 10},
                              {"QuickStep 20", "quick", 20},  {"QuickStep 50", "quick", 50},
                              {"QuickStep 100", "quick", 100}, {"QuickStep 200", "quick", 200}};
  const Scenario scenarios[] = {{"hold", false, false, 5 * scale, 1},
                                {"stretch", true, false, 8 * scale, 5},
                                {"drive", false, true, 10 * scale, 1},
                                {"stretch+drive", true, true, 10 * scale, 3}};
  std::printf("%-22s %-14s %-14s %-8s %9s %9s %9s %8s %7s\n", "world", "stepper", "scenario",
              "verdict", "joint mm", "still m/s", "vert m/s", "dist m", "wall s");
  int unstable_runs = 0;
  for (const std::string& path : worlds) {
    model::WorldLoadResult loaded = model::LoadWorldFile(path);
    if (!loaded.world) {
      std::cerr << loaded.diagnostics.Format() << "\n";
      return 2;
    }
    const std::string name = std::filesystem::path(path).filename().string();
    for (const Setting& setting : settings) {
      Parameters params;
      params.stepper = setting.stepper;
      if (setting.iterations > 0) params.quickStepIterations = setting.iterations;
      bool all_stable = true;
      for (const Scenario& scenario : scenarios) {
        const Outcome o = Run(*loaded.world, params, scenario);
        const bool stable = !o.faulted && o.max_joint_error < 5e-3 &&
                            (scenario.drive || o.max_still_speed < 1e-3);
        all_stable &= stable;
        std::printf("%-22s %-14s %-14s %-8s %9.3f %9.4f %9.4f %8.3f %7.2f", name.c_str(),
                    setting.name, scenario.name, stable ? "STABLE" : "UNSTABLE",
                    o.max_joint_error * 1e3, o.max_still_speed, o.max_vertical_speed, o.distance,
                    o.wall_seconds);
        if (o.faulted) std::printf("  faulted at step %lld", static_cast<long long>(o.fault_step));
        std::printf("\n");
        std::fflush(stdout);
      }
      if (!all_stable) ++unstable_runs;
    }
  }
  std::printf("settings unstable on some world/scenario: %d\n", unstable_runs);
  return 0;
}
