// Text helpers every program shares: trimming, and numbers written the few
// ways our messages, files and tables write them. One place, so a message
// about a value reads the same whichever program prints it.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace simpartner {

// s without leading and trailing blanks (space, tab, CR, LF).
std::string Trim(std::string_view s);

// value with at most significant_digits significant digits, as printf's
// %g: 0.1, 1e+06, 3.14159 (6 digits). Non-finite: nan, inf, -inf.
std::string FormatNumber(double value, int significant_digits = 6);

// The shortest text that reads back as the same double (std::to_chars):
// a value written to a file or a table and read again is exact. 0 for
// -0.0.
std::string ShortestNumber(double value);

// value with a fixed number of decimals (%.Nf). Non-finite as FormatNumber.
std::string FormatFixed(double value, int decimals);

// Valid UTF-8 of at most max_bytes bytes, without NUL: what a bus message's
// text may be (message_checks.h) and what a VARCHAR/TEXT column takes.
bool FitsText(const std::string& text, size_t max_bytes);

}  // namespace simpartner
