#include "simpartner/rate_limited_log.h"

namespace simpartner {

std::optional<std::string> RateLimitedLog::Pass(const std::string& key, const std::string& line,
                                                Clock::time_point now) {
  Limit& limit = limits_[key];
  if (limit.last && now - *limit.last < period_) {
    ++limit.held_back;
    return std::nullopt;
  }
  std::string said = line;
  if (limit.held_back > 0)
    said += " (and " + std::to_string(limit.held_back) + " " + held_back_ +
            " since the last report)";
  limit.last = now;
  limit.held_back = 0;
  return said;
}

}  // namespace simpartner
