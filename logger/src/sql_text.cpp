#include "simpartner/logger/sql_text.h"

#include <charconv>
#include <cmath>

namespace simpartner::logger {

void AppendDouble(std::string* out, double value) {
  if (!std::isfinite(value)) {
    out->append("NULL");
    return;
  }
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out->append(text, result.ptr);
}

void AppendInt(std::string* out, int64_t value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out->append(text, result.ptr);
}

void AppendQuoted(std::string* out, std::string_view text) {
  out->push_back('\'');
  for (const char c : text) {
    switch (c) {
      case '\0': out->append("\\0"); break;
      case '\n': out->append("\\n"); break;
      case '\r': out->append("\\r"); break;
      case '\032': out->append("\\Z"); break;
      case '\\': out->append("\\\\"); break;
      case '\'': out->append("\\'"); break;
      case '"': out->append("\\\""); break;
      default: out->push_back(c);
    }
  }
  out->push_back('\'');
}

std::string Quoted(std::string_view text) {
  std::string out;
  AppendQuoted(&out, text);
  return out;
}

void AppendTsvField(std::string* out, std::string_view text) {
  for (const char c : text) {
    switch (c) {
      case '\t': out->append("\\t"); break;
      case '\n': out->append("\\n"); break;
      case '\\': out->append("\\\\"); break;
      case '\0': out->append("\\0"); break;
      default: out->push_back(c);
    }
  }
}

}  // namespace simpartner::logger
