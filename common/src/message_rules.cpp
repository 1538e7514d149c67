#include "message_rules.h"

#include <cmath>

#include "simpartner/text.h"

namespace simpartner::message_rules {

MessageRules MessageRules::In(const char* array, size_t index) const {
  MessageRules in = *this;
  in.prefix_ = std::string(array) + "[" + std::to_string(index) + "].";
  in.array_ = array;
  in.index_ = static_cast<int64_t>(index);
  return in;
}

MessageRules MessageRules::Nested(const char* field) const {
  MessageRules in = *this;
  in.prefix_ += std::string(field) + ".";
  return in;
}

MessageProblem MessageRules::Problem(MessageFault fault, const std::string& field,
                                     const std::string& rest) const {
  MessageProblem p;
  p.type = type_;
  p.field = prefix_ + field;
  p.fault = fault;
  p.message = p.field + rest;
  p.array = array_;
  p.index = index_;
  return p;
}

MessageCheck MessageRules::Finite(const char* field, double value) const {
  if (std::isfinite(value)) return std::nullopt;
  return Problem(MessageFault::kNonFinite, field, " = " + FormatNumber(value));
}

MessageCheck MessageRules::Finite(const char* field, const double* values, size_t n) const {
  for (size_t k = 0; k < n; ++k)
    if (!std::isfinite(values[k]))
      return Problem(MessageFault::kNonFinite, std::string(field) + "[" + std::to_string(k) + "]",
                     " = " + FormatNumber(values[k]));
  return std::nullopt;
}

MessageCheck MessageRules::NotNaN(const char* field, const double* values, size_t n) const {
  for (size_t k = 0; k < n; ++k)
    if (std::isnan(values[k]))
      return Problem(MessageFault::kNonFinite, std::string(field) + "[" + std::to_string(k) + "]",
                     " = nan");
  return std::nullopt;
}

MessageCheck MessageRules::UnitQuaternion(const char* field, const double q[4]) const {
  if (auto bad = Finite(field, q, 4)) return bad;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (std::abs(norm - 1) <= kUnitTolerance) return std::nullopt;
  return Problem(MessageFault::kNotUnit, field,
                 " has length " + FormatNumber(norm) + " (a unit quaternion is needed)");
}

MessageCheck MessageRules::UnitVector(const char* field, const double v[3]) const {
  const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (std::isfinite(norm) && std::abs(norm - 1) <= kUnitTolerance) return std::nullopt;
  return Problem(MessageFault::kNotUnit, field, " = " + Triple(v) + " is not a unit vector");
}

MessageCheck MessageRules::Index(const char* field, int64_t value, int64_t size,
                                 bool none_allowed, const char* what) const {
  if ((none_allowed && value == -1) || (value >= 0 && value < size)) return std::nullopt;
  return Problem(MessageFault::kBadIndex, field,
                 " = " + std::to_string(value) + " (no such " + what + "), the model has " +
                     std::to_string(size));
}

MessageCheck MessageRules::Text(const char* field, const std::string& text,
                                size_t max_bytes) const {
  if (FitsText(text, max_bytes)) return std::nullopt;
  return Problem(MessageFault::kBadText, field,
                 " is not valid UTF-8 of at most " + std::to_string(max_bytes) + " bytes (" +
                     std::to_string(text.size()) + " bytes)");
}

std::string Triple(const double v[3]) {
  return "(" + FormatNumber(v[0]) + ", " + FormatNumber(v[1]) + ", " + FormatNumber(v[2]) + ")";
}

}  // namespace simpartner::message_rules
