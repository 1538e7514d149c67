// Numbers as text for the files we write: the shortest form that reads
// back as the same double, so a converted mass or inertia is exact.
#pragma once

#include <charconv>
#include <string>

namespace simpartner::convert {

inline std::string NumberText(double value) {
  if (value == 0.0) return "0";  // no "-0"
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace simpartner::convert
