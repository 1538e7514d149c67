// The rules the message checks (message_checks.h) are written in: each
// returns the problem naming the field and its value, or nothing. A
// MessageRules knows the message type and the field prefix it checks
// under ("bodies[3]."), so every check names its field in full.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "simpartner/message_problem.h"

namespace simpartner::message_rules {

// Longest texts, as the logger's columns hold them (VARCHAR(255),
// VARCHAR(1024), TEXT); no reader needs longer.
inline constexpr size_t kNameBytes = 255;
inline constexpr size_t kPathBytes = 1024;
inline constexpr size_t kTextBytes = 65535;
// How far from 1 a unit quaternion or direction may be: doubles from the
// sim are unit to ~1e-15; this lets honest rounding through and catches a
// zero or unnormalised one.
inline constexpr double kUnitTolerance = 1e-3;

class MessageRules {
 public:
  explicit MessageRules(const char* type) : type_(type) {}

  // The rules for element `index` of the top-level array `array`.
  MessageRules In(const char* array, size_t index) const;
  // The rules for a nested struct field ("geometry").
  MessageRules Nested(const char* field) const;

  MessageCheck Finite(const char* field, double value) const;
  MessageCheck Finite(const char* field, const double* values, size_t n) const;
  MessageCheck NotNaN(const char* field, const double* values, size_t n) const;
  MessageCheck UnitQuaternion(const char* field, const double q[4]) const;
  MessageCheck UnitVector(const char* field, const double v[3]) const;
  // `value` indexes an element of `size` `what`s ("body"), or is -1 when
  // `none_allowed`.
  MessageCheck Index(const char* field, int64_t value, int64_t size, bool none_allowed,
                     const char* what) const;
  MessageCheck Text(const char* field, const std::string& text, size_t max_bytes) const;

  // A problem of `field` (under this prefix); `rest` follows the field's name.
  MessageProblem Problem(MessageFault fault, const std::string& field,
                         const std::string& rest) const;

 private:
  std::string type_;
  std::string prefix_;  // "bodies[3]." or ""
  std::string array_;
  int64_t index_ = -1;
};

// "(0, 1, nan)"
std::string Triple(const double v[3]);

}  // namespace simpartner::message_rules
