// What is wrong with a bus message that decoded (bus_decode.h) but cannot
// be taken: the one result every message check returns (message_checks.h),
// so every process refuses the same messages and names them the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace simpartner {

// Which kind of rule a message broke, for processes that count refusals
// by kind (the viewer's HUD).
enum class MessageFault {
  kNonFinite,      // NaN or infinity where a number is needed
  kNotUnit,        // a quaternion or direction far from unit length
  kOutOfRange,     // a number outside what its field allows
  kBadIndex,       // an index naming no element of the model
  kCountMismatch,  // an array's length is not the model's
  kBadText,        // a string that is not UTF-8 or is too long
  kUnknownValue,   // a value the .lcm file does not define (a kind, a format)
  kNotTheModels,   // a name or kind that differs from the model's element
};

struct MessageProblem {
  std::string type;   // the LCM type: "model_t"
  std::string field;  // the field, with indices: "bodies[3].initial_orientation"
  MessageFault fault = MessageFault::kOutOfRange;
  // What is wrong, starting with the field and naming its value:
  // "bodies[3].initial_orientation has length 1.7 (a unit quaternion is needed)".
  std::string message;
  // The element of a top-level array the field belongs to ("bodies", 3),
  // so a caller holding the model can name it; "" and -1 when none.
  std::string array;
  int64_t index = -1;

  // "model_t.bodies[3].initial_orientation has length 1.7 (...)": for
  // places without a channel to name.
  std::string Format() const { return type + "." + message; }
};

// Nothing when the message may be taken.
using MessageCheck = std::optional<MessageProblem>;

}  // namespace simpartner
