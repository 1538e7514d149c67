// Whether a decoded bus message (bus_decode.h) may be taken: one check per
// message type, which every process that reads the type applies, so a
// malformed message is refused by all of them or by none. Each returns
// the first problem, naming the field and its value (message_problem.h).
//
// What is checked is the message's own structure and, given its model,
// that it fits that model (counts, indices, sensor kinds and names).
// Whether it belongs to the simulation a process follows, and whatever
// else only one process needs (the logger's step rate, the camera's
// renderable cameras), stays with that process.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/image_t.hpp"
#include "simpartner/message_problem.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/soil_ruts_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner {

// A model_t: texts are UTF-8 and bounded; numbers finite; step_size above
// 0 and state_every at least 1; up and every quaternion unit; a plane's
// normal not zero; geometry kinds known with sizes in (0, 100 km];
// material enums known; every robot, body and joint index names one (or
// is -1 where the .lcm file allows); a heightfield of at least 2 x 2
// samples that match rows x columns, at most 16 Mi of them.
MessageCheck CheckModel(const model_t& model);

// What the other messages of a simulation must fit: its model's counts
// and sensors, small enough to keep per simulation.
struct ModelOutline {
  struct Sensor {
    int8_t kind = 0;
    std::string name;
  };
  int64_t simulation_id = 0;
  int32_t bodies = 0;
  int32_t joints = 0;
  std::vector<Sensor> sensors;
};
ModelOutline OutlineOf(const model_t& model);

// A state_t: step >= 0; sim_time, poses, contact forces, joint positions,
// rates, anchors, forces and wheel-on-soil figures finite; orientations
// unit. With `model` (nullptr when not known yet), also as many bodies
// and joints as it has and every wheel a body of it.
MessageCheck CheckState(const state_t& state, const ModelOutline* model);

// A sensor_reading_t: sim_time and values finite, text UTF-8 of at most
// 65535 bytes. With `model`, also a sensor of it, of its kind and name.
MessageCheck CheckSensorReading(const sensor_reading_t& reading, const ModelOutline* model);

// A status_t: sim_time and real_time_factor finite.
MessageCheck CheckStatus(const status_t& status);

// An image_t: a known format, 1 to 4096 pixels a side, num_bytes width x
// height x bytes per pixel. With `model`, also that `camera` is a camera
// sensor of it with the image's name, the format colour or the camera's
// depth format, and the sides at most the camera's resolution.
MessageCheck CheckImage(const image_t& image, const model_t* model);

// A soil_ruts_t: part within parts; origin, up and u_axis finite, up and
// u_axis unit and perpendicular; cell_size 1 mm to 1 m; a known ground;
// every depth above 0 and at most kMaxRutDepth.
inline constexpr double kMaxRutDepth = 10.0;  // [m]
MessageCheck CheckSoilRuts(const soil_ruts_t& ruts);

// A command_t's texts (sender, robot, target, text): UTF-8, at most 255
// bytes (65535 the text). What its values mean is the sim's to judge.
MessageCheck CheckCommand(const command_t& command);

// A command_reply_t's texts (sender, target, reason, previous_text):
// UTF-8, at most 255 bytes (65535 the reason and previous_text).
MessageCheck CheckCommandReply(const command_reply_t& reply);

}  // namespace simpartner
