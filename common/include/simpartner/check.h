// Internal invariants. SP_CHECK is always on (also in Release) because a
// simulator whose numbers are trusted must not run on with a broken
// invariant; user input is validated separately and reported as a
// DiagnosticError with its location.
#pragma once

#include <stdexcept>
#include <string>

namespace simpartner {

// An internal invariant failed: a bug in SimPartner, not bad input.
class InternalError : public std::logic_error {
 public:
  explicit InternalError(const std::string& what) : std::logic_error(what) {}
};

[[noreturn]] void ThrowInternalError(const char* condition, const char* func,
                                     const char* file, int line,
                                     const std::string& detail);

}  // namespace simpartner

#define SP_CHECK(condition)                                                   \
  do {                                                                        \
    if (!(condition))                                                         \
      ::simpartner::ThrowInternalError(#condition, __func__, __FILE__,        \
                                       __LINE__, std::string());              \
  } while (false)

#define SP_CHECK_MSG(condition, detail)                                       \
  do {                                                                        \
    if (!(condition))                                                         \
      ::simpartner::ThrowInternalError(#condition, __func__, __FILE__,        \
                                       __LINE__, (detail));                   \
  } while (false)
