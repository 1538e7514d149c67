// Text for the XML files the converter writes: numbers in the shortest
// form that reads back as the same double (a converted mass or inertia is
// exact), and attribute or text content escaped.
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

inline std::string EscapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace simpartner::convert
