// Text of SQL statements and LOAD DATA files: numbers in their shortest
// exact form, strings quoted and escaped. Batches of rows are built as text
// (one multi-row INSERT or one LOAD DATA file per table), so these run
// about a hundred thousand times a second.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace simpartner::logger {

// Shortest decimal text that reads back as the same double. Non-finite
// values (which the receiver refuses before they get here) become NULL.
void AppendDouble(std::string* out, double value);
void AppendInt(std::string* out, int64_t value);
// 'text' with \, ', ", NUL, newline, return and Ctrl-Z escaped (the
// server's default sql_mode, which the writer sets for its session).
void AppendQuoted(std::string* out, std::string_view text);
std::string Quoted(std::string_view text);
// A field of a LOAD DATA file with the default FIELDS ESCAPED BY '\\':
// tab, newline and backslash escaped.
void AppendTsvField(std::string* out, std::string_view text);

}  // namespace simpartner::logger
