// Drive WorkPartner (gen1 or gen3) in a circle with its articulation joint:
// steer the Turner joint with its angle controller, drive each side at the
// speed the steering geometry asks, and measure the radius from SIM_STATE.
// Usage: drive_circle [--lcm-url URL] [--alpha RAD]
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "simpartner/client/client.h"
#include "simpartner/command_line.h"

using namespace simpartner::client;

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "drive_circle";
  spec.summary = "Drives WorkPartner (gen1 or gen3) in a circle and prints its radius.";
  spec.options = {simpartner::Text("lcm-url", "URL", "the bus (default: the sim's default)"),
                  simpartner::Number("alpha", "RAD", "steering angle, + turns left (default 0.2972)")};
  simpartner::CommandLine args;
  if (auto done = simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  ClientOptions options;
  options.program = "drive_circle";
  options.url = args.Text("lcm-url", options.url);
  const double alpha = args.Number("alpha", 0.2972);  // [rad], + turns left
  // WorkPartner's geometry (SPEC 7): Turner joint to each axle, half the
  // track, wheel radius; and the speed of the axle midpoints [m/s].
  const double a = 0.6, half_track = 0.3, wheel_radius = 0.235, speed = 1.0;
  try {
    Client client(options);  // connects and learns the model (NoSim if none)
    const auto model = client.catalog();
    // Steer and hold the angle stiffly (P, I, D) against the wheels' forces.
    client.Command(SetAngle(client.Find("TurnerMotor"), {alpha}, 100, 100, 0));
    // Both axle midpoints circle at r = a cot(alpha/2). Equal wheel speeds
    // would make the wheels scrub (and the turn wider): the inner side
    // (wheels 2 and 3 in a left turn) rolls on r - half_track.
    const double r = a / std::tan(alpha / 2);
    const double inner = speed * (r - half_track) / r / wheel_radius;  // [rad/s]
    const double outer = speed * (r + half_track) / r / wheel_radius;
    command_reply_t reply;
    for (int w = 1; w <= 4; ++w) {
      const Target motor = client.Find("Axle" + std::to_string(w) + "Motor");
      reply = client.Command(SetVelocity(motor, {w == 2 || w == 3 ? inner : outer}));
    }
    // The rear axle midpoint at three sim times once the turn has settled,
    // and the circle through the three points.
    const int w3 = model->BodyIndex("Wheel3"), w4 = model->BodyIndex("Wheel4");
    const double start = reply.applied_at_step * model->step_size() + 3.0;
    double x[3], z[3];  // the ground is the x-z plane (y up)
    for (int k = 0; k < 3; ++k) {
      const state_t s = client.WaitUntilSimTime(start + 2.0 * k, 60.0);
      x[k] = (s.bodies[w3].position[0] + s.bodies[w4].position[0]) / 2;
      z[k] = (s.bodies[w3].position[2] + s.bodies[w4].position[2]) / 2;
    }
    const double ab = std::hypot(x[1] - x[0], z[1] - z[0]);
    const double bc = std::hypot(x[2] - x[1], z[2] - z[1]);
    const double ca = std::hypot(x[0] - x[2], z[0] - z[2]);
    const double area2 = std::abs((x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0]));
    const double radius = ab * bc * ca / (2 * area2);
    std::printf("radius %.4f m (steering geometry a cot(alpha/2): %.4f m)\n", radius, r);
    for (const command_t& stop : StopWheelsCommands(*model)) client.Command(stop);
    return 0;
  } catch (const ClientError& e) {
    std::fprintf(stderr, "drive_circle: %s\n", e.what());
    return 1;
  }
}
