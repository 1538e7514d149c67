// What the field sensors cost per step: the shipped gen3 (or
// the world given) stepped with
//   none        the thesis's sensors only (the new kinds taken out)
//   imu+gnss+enc  plus its IMU (100 Hz), GNSS (10 Hz) and four wheel
//               encoders (100 Hz): the target, at most 5 % over none
//   all         plus its lidar too (4 x 221 rays at 12.5 Hz)
// each step followed by taking the readings and encoding them as
// SIM_SENSOR messages (the sim's part of publishing them). The variants
// run interleaved, in rounds of --steps steps, timed by this thread's CPU
// clock so that other load on the machine counts less; the median round
// is printed. Wheels turn at 1 rad/s so that the sensors see motion.
//   bench/sensor_bench [--rounds N] [--steps N] [--engine ode|mujoco] [world.xml]
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/sensor_parameters.h"
#include "simpartner/sim/simulation.h"

#include "rounds.h"

namespace {

using namespace simpartner;
using bench::Median;
using bench::ThreadCpuSeconds;

// The world with only the sensors `keep` accepts.
template <class Keep>
model::World WithSensors(model::World world, Keep keep) {
  for (model::RobotInstance& r : world.robots) {
    std::vector<model::Sensor> kept;
    for (const model::Sensor& s : r.robot.sensors)
      if (keep(s)) kept.push_back(s);
    r.robot.sensors = kept;
  }
  return world;
}

struct Variant {
  const char* name;
  std::unique_ptr<sim::Simulation> sim;
  std::vector<double> micros_per_step;  // one per round
  long readings = 0;
  long bytes = 0;
};

command_t Drive(const std::string& motor) {
  command_t c{};
  c.sender = "sensor_bench";
  c.target = motor;
  c.action = command_t::ACTION_SET;
  c.apply_at_step = -1;
  c.values = {1000, 1.0};
  c.num_values = 2;
  return c;
}

void Round(Variant* v, int steps) {
  std::vector<uint8_t> buffer;
  const double start = ThreadCpuSeconds();
  for (int n = 0; n < steps; ++n) {
    v->sim->Step();
    for (const sensor_reading_t& r : v->sim->TakeSensorReadings()) {
      buffer.resize(static_cast<size_t>(r.getEncodedSize()));
      v->bytes += r.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
      ++v->readings;
    }
  }
  v->micros_per_step.push_back((ThreadCpuSeconds() - start) * 1e6 / steps);
}

}  // namespace

int main(int argc, char** argv) {
  CommandLineSpec spec;
  spec.program = "sensor_bench";
  spec.summary =
      "Microseconds per step of a world (default: the shipped gen3) without its field sensors,\n"
      "with its IMU, GNSS and encoders, and with all of them (lidar too), readings taken and\n"
      "encoded; interleaved rounds timed by thread CPU time, the median round printed.";
  spec.options = {
      Integer("rounds", "N", "rounds per variant (default 15)").Range(1, 1e6),
      Integer("steps", "N", "steps per round (default 1000)").Range(1, 1e9),
      Text("engine", "NAME", "physics engine (default ode)").Choices({"ode", "mujoco"}),
  };
  spec.positionals = {Positional{"world.xml", 0, 1}};
  CommandLine args;
  if (const auto done = ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const int rounds = static_cast<int>(args.Integer("rounds", 15));
  const int steps = static_cast<int>(args.Integer("steps", 1000));
  Parameters params;
  params.engine = args.Text("engine", "ode");
  const std::string world_path = args.positional().empty()
                                     ? std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml"
                                     : args.positional()[0];
  try {
    const model::World world = model::LoadWorldOrThrow(world_path);
    const auto old_kind = [](const model::Sensor& s) { return !model::NeedsRate(s.kind); };
    Variant variants[3] = {
        {"none", nullptr, {}, 0, 0}, {"imu+gnss+enc", nullptr, {}, 0, 0}, {"all", nullptr, {}, 0, 0}};
    variants[0].sim = std::make_unique<sim::Simulation>(WithSensors(world, old_kind), params, 1);
    variants[1].sim = std::make_unique<sim::Simulation>(
        WithSensors(world, [](const model::Sensor& s) { return s.kind != model::SensorKind::kLidar; }),
        params, 1);
    variants[2].sim = std::make_unique<sim::Simulation>(world, params, 1);
    for (Variant& v : variants) {
      for (const char* motor : {"Axle1Motor", "Axle2Motor", "Axle3Motor", "Axle4Motor"})
        v.sim->Submit(Drive(motor));
      Round(&v, 500);  // warm up
      v.micros_per_step.clear();
      v.readings = v.bytes = 0;
    }
    for (int r = 0; r < rounds; ++r)
      for (Variant& v : variants) Round(&v, steps);
    std::printf("%s, engine %s, %d rounds of %d steps (median round, thread CPU time)\n",
                world_path.c_str(), params.engine.c_str(), rounds, steps);
    std::printf("%-14s %10s %10s %14s %14s\n", "sensors", "us/step", "over none", "readings/step",
                "bytes/step");
    const double base = Median(variants[0].micros_per_step);
    for (const Variant& v : variants) {
      const double us = Median(v.micros_per_step);
      const double total_steps = static_cast<double>(rounds) * steps;
      std::printf("%-14s %10.1f %+9.2f%% %14.3f %14.1f\n", v.name, us, 100.0 * (us / base - 1.0),
                  static_cast<double>(v.readings) / total_steps,
                  static_cast<double>(v.bytes) / total_steps);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sensor_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
