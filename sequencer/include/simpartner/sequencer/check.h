// A parsed sequence checked against a model (the one the sim announces on
// the bus, or one built offline from a world file): every name and port
// exists, every command has the number of values its target's kind takes,
// waits name joints and sensor values that exist. The result is the plan
// the player sends, command_t by command_t.
#pragma once

#include <string>
#include <vector>

#include "simpartner/client/catalog.h"
#include "simpartner/command_t.hpp"
#include "simpartner/diagnostic.h"
#include "simpartner/model/model.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sequencer/sequence.h"

namespace simpartner::sequencer {

struct PlannedCommand {
  const Command* source = nullptr;  // file line, element, time
  client::Target target;
  command_t message;                // built by the client library; apply_at_step set when sent
};

struct PlannedWait {
  const Wait* source = nullptr;
  int joint = -1;                   // index into state_t.joints
  int sensor = -1;                  // index into model_t.sensors
  std::string sensor_name;
  bool read_on_request = false;     // the sensor publishes only when asked
};

struct PlannedSegment {
  std::vector<PlannedCommand> commands;
  const Segment* source = nullptr;
  PlannedWait wait;                 // when source->wait is set
};

struct Plan {
  std::vector<PlannedSegment> segments;
  std::vector<client::Target> wheel_motors;  // velocity-controlled actuators, stopped on failure
};

// Checks `sequence` against the model; fills *plan when there are no
// diagnostics. Every problem is `file:line: element: message`.
DiagnosticList CheckSequence(const Sequence& sequence, const model_t& model, Plan* plan);

// The world file a sequence names (Sequence::world): a relative name is
// looked for next to the sequence first, then as simpartner-sim finds
// --environment (model::FindWorldFile: as given, then among the shipped
// models/worlds/). "" when the sequence names none. Throws ConfigError at
// the sequence's root, listing every path tried, when it is not found.
std::string FindSequenceWorld(const Sequence& sequence);

// The world to check or play a sequence against: given (a world file
// found already; "" for none) or else the one the sequence names, found
// as above. Throws ConfigError naming both when the sequence names
// another world than the given one.
std::string WorldForSequence(const Sequence& sequence, const std::string& given);

// The model the sim would announce for a world, built without the physics
// (model::ModelMessageFromWorld, shared with teleop's --check).
model_t ModelFromWorld(const model::World& world);

}  // namespace simpartner::sequencer
