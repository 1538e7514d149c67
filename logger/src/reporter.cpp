#include "simpartner/logger/reporter.h"

namespace simpartner::logger {

void Reporter::Say(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  *out_ << program_ << ": " << line << std::endl;
}

void Reporter::SayLimited(const std::string& key, const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  Limit& limit = limits_[key];
  const Clock::time_point now = Clock::now();
  if (limit.last != Clock::time_point{} && now - limit.last < limit_period_) {
    ++limit.held_back;
    return;
  }
  *out_ << program_ << ": " << line;
  if (limit.held_back > 0)
    *out_ << " (and " << limit.held_back << " more like it since the last report)";
  *out_ << std::endl;
  limit.last = now;
  limit.held_back = 0;
}

}  // namespace simpartner::logger
