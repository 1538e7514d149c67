// What only the client tests share (the rest is tests/support/): reading a
// number a program printed.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace simpartner::client::testing {

// The number printed right after `label` in `text` (GCC 12 warns falsely
// inside <regex> under the sanitizers, so no std::regex here).
inline std::optional<double> NumberAfter(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  if (at == std::string::npos) return std::nullopt;
  const char* start = text.c_str() + at + label.size();
  char* end = nullptr;
  const double value = std::strtod(start, &end);
  if (end == start) return std::nullopt;
  return value;
}

}  // namespace simpartner::client::testing
