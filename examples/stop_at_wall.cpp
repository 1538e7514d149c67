// Drive WorkPartner (gen2 or gen3) forward until its laser scanner sees
// something within 1 m, then stop the wheels: a closed loop on SIM_SENSOR.
// Try it in models/worlds/scanner_wall.xml (a wall 5.3 m ahead).
// Usage: stop_at_wall [--lcm-url URL]
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

#include "simpartner/client/client.h"
#include "simpartner/command_line.h"

using namespace simpartner::client;

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "stop_at_wall";
  spec.summary = "Drives WorkPartner forward until its scanner sees something within 1 m.";
  spec.options = {simpartner::Text("lcm-url", "URL", "the bus (default: the sim's default)")};
  simpartner::CommandLine args;
  if (auto done = simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  ClientOptions options;
  options.program = "stop_at_wall";
  options.url = args.Text("lcm-url", options.url);
  const double stop_distance = 1.0;        // [m]
  const double wheel_speed = 1.0 / 0.235;  // [rad/s]: 1 m/s on 0.235 m wheels
  try {
    Client client(options);
    const auto model = client.catalog();
    // The scanner publishes on request only unless given a rate [Hz].
    const Target scanner = client.Find("Scanner");
    client.Command(BuildCommand(scanner, command_t::ACTION_SENSOR_PARAMS, {100.0}));
    for (int w = 1; w <= 4; ++w)
      client.Command(SetVelocity(client.Find("Axle" + std::to_string(w) + "Motor"), {wheel_speed}));
    // Each new scan: the nearest thing any ray sees (max range = nothing).
    int64_t step = -1;
    double nearest = 0;
    do {
      const sensor_reading_t scan = client.WaitForReading("Scanner", step, 30.0);
      step = scan.step;
      nearest = *std::min_element(scan.values.begin(), scan.values.end());
    } while (nearest > stop_distance);
    for (const command_t& stop : StopWheelsCommands(*model)) client.Send(stop);
    std::printf("stopping: something at %.3f m (sim time %.3f s)\n", nearest,
                step * model->step_size());
    // Wait until the robot stands still, then report the last scan.
    const double stop_time = step * model->step_size();
    client.WaitUntilSimTime(stop_time + 2.0, 30.0);
    const sensor_reading_t last = client.WaitForReading("Scanner", -1, 30.0);
    std::printf("stopped: nearest %.3f m\n", *std::min_element(last.values.begin(), last.values.end()));
    return 0;
  } catch (const ClientError& e) {
    std::fprintf(stderr, "stop_at_wall: %s\n", e.what());
    return 1;
  }
}
