#include "simpartner/text.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace simpartner {
namespace {

std::string NonFinite(double value) {
  return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
}

}  // namespace

std::string Trim(std::string_view s) {
  constexpr std::string_view kBlanks = " \t\r\n";
  const size_t begin = s.find_first_not_of(kBlanks);
  if (begin == std::string_view::npos) return "";
  return std::string(s.substr(begin, s.find_last_not_of(kBlanks) - begin + 1));
}

std::string FormatNumber(double value, int significant_digits) {
  if (!std::isfinite(value)) return NonFinite(value);
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", significant_digits, value);
  return text;
}

std::string ShortestNumber(double value) {
  if (value == 0.0) return "0";  // no "-0"
  if (!std::isfinite(value)) return NonFinite(value);
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

std::string FormatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return NonFinite(value);
  char text[400];  // %.f of 1e308 has 309 digits before the point
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

}  // namespace simpartner
