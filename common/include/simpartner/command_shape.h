// How many values a command takes, per target kind and action: the one
// rule the sim and every client check against (SPEC 5b, actuator_t.lcm).
// Shape only (counts, not ranges): ranges depend on the joint's stops and
// the sim's limits and are the sim's to check.
#pragma once

#include <string>
#include <vector>

namespace simpartner {

// What a command addresses, in the terms of the bus messages.
struct CommandTargetShape {
  bool is_sensor = false;
  int kind = 0;      // actuator_t::KIND_* or sensor_t::KIND_*
  int num_axes = 1;  // axes of the driven joint (actuators)
};

// The accepted value counts for `action` (command_t::ACTION_*) on `target`,
// e.g. {6, 2} for a one-axis velocity controller's SET (three slots x, y, z
// or per axis). An empty list: the action does not apply to the target.
// A value of -1 in the list means "any text" (an echo sensor's SET).
std::vector<int> AcceptedValueCounts(const CommandTargetShape& target, int action);

// The meaning of each value of one accepted form, for usage text and
// messages: {"max force x", ..., "velocity z"} (slot form) or per axis.
std::vector<std::string> ValueNames(const CommandTargetShape& target, int action, int count);

// "fmax_x,fmax_y,fmax_z,vel_x,vel_y,vel_z (6) or fmax,vel (2)" for help
// output and errors; "" when the action does not apply.
std::string DescribeValueForms(const CommandTargetShape& target, int action);

// Empty when `count` values fit; otherwise why, e.g. "expected 6 values
// (three slots x, y, z) or 2 (per axis), got 3".
std::string CheckValueCount(const CommandTargetShape& target, int action, int count);

// The spellings of one action (command_t::ACTION_*), in one table because
// three places spell it: a client's command word and messages ("stops"),
// a version-2 sequence file's element ("<stops>"), and the logger's
// Command.action column ("SET_STOPS", the lcm constant's name).
struct ActionSpelling {
  int action;
  const char* word;              // "set", "hold", "stops", "params", "read"
  const char* sequence_element;  // "set", "hold", "stops", "sensorParams", "read"
  const char* database;          // "SET", "HOLD", "SET_STOPS", "SENSOR_PARAMS", "READ"
};

// The five actions, in command_t::ACTION_* order.
const std::vector<ActionSpelling>& ActionSpellings();

// The spellings of action; for a value outside the table the words are
// "unknown action" and the database name "UNKNOWN".
const ActionSpelling& SpellAction(int action);

// The action a sequence element names, or -1 when it names none.
int ActionOfSequenceElement(const std::string& element);

// Name of an action for messages: SpellAction(action).word.
inline const char* ActionName(int action) { return SpellAction(action).word; }

}  // namespace simpartner
