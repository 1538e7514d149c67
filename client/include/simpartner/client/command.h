// Building command_t messages from a Target: values checked for the
// target's kind and action before anything is sent, in the same shapes the
// sim accepts (common/command_shape.h). No transport: the client, the
// sequencer and the validation's timed commands all build here. The
// transport fills utime, request_id and sender.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "simpartner/client/catalog.h"
#include "simpartner/command_t.hpp"

namespace simpartner::client {

// Largest encoded command_t we send: a UDP multicast datagram above this
// is fragmented by LCM and easily lost.
inline constexpr size_t kMaxCommandBytes = 60 * 1024;
// Force limit used by the convenience builders when none is given
// (SPEC 4: actuators hold with 1000 per axis).
inline constexpr double kDefaultMaxForce = 1000.0;

// Parses the original's comma-separated numbers ("1000,1000,100,0,0,0.2").
// Throws BadValues naming the item, e.g. field "values[2]" value "x".
std::vector<double> ParseValueText(const std::string& target_name, const std::string& text);

// The command for `target`: addressed by robot and name (never by port, so
// the reply names the target), values as given. Throws BadValues when the
// count does not fit the target's kind and action, a value is not finite,
// or the encoded message would exceed kMaxCommandBytes.
command_t BuildCommand(const Target& target, int action, const std::vector<double>& values,
                       int64_t apply_at_step = -1);
// The same from the original's text form; an Echo sensor's SET keeps the
// text as its echo. Throws BadValues as above.
command_t BuildCommandFromText(const Target& target, int action, const std::string& text,
                               int64_t apply_at_step = -1);

// Convenience forms (per-axis, short form).
// Velocity controller or linear motor: velocity per axis, one force limit.
command_t SetVelocity(const Target& target, const std::vector<double>& velocity,
                      double max_force = kDefaultMaxForce, int64_t apply_at_step = -1);
// Angle controller: target angle per axis with P, I, D gains.
command_t SetAngle(const Target& target, const std::vector<double>& angle, double p, double i,
                   double d, double max_force = kDefaultMaxForce, int64_t apply_at_step = -1);
// Hold the current position (optional force limit per axis).
command_t Hold(const Target& target, double max_force = kDefaultMaxForce,
               int64_t apply_at_step = -1);
// Ask a sensor for a reading now.
command_t Read(const Target& target, int64_t apply_at_step = -1);

// Zero velocity for every velocity-controlled actuator of the catalog (the
// wheel motors): what a sequence or teleop sends when it stops.
std::vector<command_t> StopWheelsCommands(const Catalog& catalog,
                                          double max_force = kDefaultMaxForce);

// Bytes the command takes on the bus.
size_t EncodedSize(const command_t& command);

}  // namespace simpartner::client
