// A closed loop in lock-step: drive WorkPartner (gen1 or gen3) to a point,
// steering the Turner joint from the measured heading every tick. Started
// on a paused sim (simpartner-sim --startPaused=1), the run repeats bit
// for bit at any speed: the same commands land in the same steps.
// PERIOD_STEPS 0 runs the same controller without lock-step, as control
// code usually runs: it reads the newest state every 10 ms of sim time
// and its commands land whenever they arrive (runs differ).
// Usage: drive_to_point [--lcm-url URL] [--x X] [--z Z] [--period STEPS]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "simpartner/client/client.h"
#include "simpartner/client/lock_step.h"
#include "simpartner/command_line.h"

using namespace simpartner::client;

// Heading of a y-up robot facing +x in its body frame: its yaw about y,
// positive to the left (towards -z) [rad].
double Heading(const body_state_t& body) {
  const double w = body.orientation[0], x = body.orientation[1], y = body.orientation[2],
               z = body.orientation[3];
  const double forward_x = 1 - 2 * (y * y + z * z), forward_z = 2 * (x * z - w * y);
  return std::atan2(-forward_z, forward_x);
}

// The commands for one state; true when the goal is reached (or given up).
struct Goal {
  double x, z;
};

bool Decide(Client& sim, const state_t& s, const Goal& goal) {
  static const char* kWheels[] = {"Axle1Motor", "Axle2Motor", "Axle3Motor", "Axle4Motor"};
  const body_state_t& body = s.bodies[static_cast<size_t>(sim.catalog()->BodyIndex("FrontChassis"))];
  const double dx = goal.x - body.position[0], dz = goal.z - body.position[2];
  const double distance = std::hypot(dx, dz);
  if (distance < 0.2 || s.sim_time > 60) {
    std::printf("tick %lld, t = %.3f s: front at (%.4f, %.4f), %.3f m from the goal\n",
                static_cast<long long>(s.step), s.sim_time, body.position[0], body.position[2],
                distance);
    for (const command_t& stop : StopWheelsCommands(*sim.catalog())) sim.Send(stop);
    return true;
  }
  // Steer towards the goal (the Turner joint turns left for + angles), and
  // slow down on the last metre.
  const double error = std::remainder(std::atan2(-dz, dx) - Heading(body), 2 * M_PI);
  sim.Send(SetAngle(sim.Find("TurnerMotor"), {std::clamp(1.5 * error, -0.35, 0.35)}, 100, 100, 0));
  const double speed = std::min(3.0, 1.0 + 2.0 * distance);  // wheel rate [rad/s]
  for (const char* wheel : kWheels) sim.Send(SetVelocity(sim.Find(wheel), {speed}));
  return false;
}

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "drive_to_point";
  spec.summary = "Drives WorkPartner (gen1 or gen3) to a point in lock-step, steering from its heading.";
  spec.options = {
      simpartner::Text("lcm-url", "URL", "the bus (default: the sim's default)"),
      simpartner::Number("x", "M", "the goal's x [m] (default 4)"),
      simpartner::Number("z", "M", "the goal's z [m] (default -3)"),
      simpartner::Integer("period", "STEPS",
                          "steps between ticks (default 10); 0: without lock-step").Range(0, 1000000)};
  simpartner::CommandLine args;
  if (auto done = simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  ClientOptions options;
  options.program = "drive_to_point";
  options.url = args.Text("lcm-url", options.url);
  const Goal goal{args.Number("x", 4.0), args.Number("z", -3.0)};
  LockStepOptions loop_options;
  loop_options.period = args.Integer("period", 10);  // 100 Hz at 1 ms steps
  try {
    Client sim(options);
    if (loop_options.period == 0) {  // without lock-step
      sim.Resume();
      for (double t = 0;; t += 0.01)
        if (Decide(sim, sim.WaitUntilSimTime(t, 10), goal)) return 0;
    }
    LockStep loop(sim, loop_options);  // joins; resumes a paused sim
    while (!Decide(sim, loop.Next(), goal)) {
    }
    loop.Next();  // the stop applies in the step after the last tick
    return 0;
  } catch (const SimStopped& e) {
    std::printf("%s\n", e.what());  // its duration reached: a batch run's end
    return 0;
  } catch (const ClientError& e) {
    std::fprintf(stderr, "drive_to_point: %s\n", e.what());
    return 1;
  }
}
