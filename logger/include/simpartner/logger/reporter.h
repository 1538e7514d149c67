// Lines for the person running the logger, from any thread, with a limit
// on how often the same complaint repeats (a flood of bad messages must
// not become a flood of output: common/rate_limited_log.h).
#pragma once

#include <chrono>
#include <mutex>
#include <ostream>
#include <string>

#include "simpartner/rate_limited_log.h"

namespace simpartner::logger {

class Reporter {
 public:
  using Clock = std::chrono::steady_clock;
  // Repeats of a limited line are held back for `limit_period`.
  Reporter(std::ostream* out, std::string program,
           Clock::duration limit_period = std::chrono::seconds(5))
      : out_(out), program_(std::move(program)), limited_(limit_period) {}

  // "program: line"
  void Say(const std::string& line);
  // Says the line unless the same key spoke within the limit period; the
  // lines held back are counted and mentioned with the next one let through.
  void SayLimited(const std::string& key, const std::string& line);

 private:
  std::ostream* out_;
  std::string program_;
  std::mutex mutex_;
  RateLimitedLog limited_;  // guarded by mutex_
};

}  // namespace simpartner::logger
