#include "simpartner/csv_field.h"

#include <cmath>
#include <cstdlib>

namespace simpartner {
namespace {

bool IsNumber(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(value);
}

bool StartsAFormula(const std::string& text) {
  return !text.empty() && std::string("=+-@\t\r").find(text.front()) != std::string::npos &&
         !IsNumber(text);
}

}  // namespace

std::string CsvField(const std::string& text) {
  const bool formula = StartsAFormula(text);
  if (!formula && text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = formula ? "\"'" : "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace simpartner
