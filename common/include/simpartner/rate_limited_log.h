// Repeated complaints said at most once per period per key: the first at
// once, then the newest one a period after the last line, saying how many
// were held back meanwhile. A flood of bad messages must not become a
// flood of output (50,000 forged ids once made 16 MB of stderr), yet what
// was held back is still counted where the next line says it.
//
// The caller gives the time (tests pass their own clock) and the keys: a
// small fixed set it names (a channel, "signature"), never text from the
// bus. Not thread-safe: its owner locks.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace simpartner {

class RateLimitedLog {
 public:
  using Clock = std::chrono::steady_clock;

  // `held_back` names what the count is of: "(and 12 <more like it> since
  // the last report)".
  explicit RateLimitedLog(Clock::duration period, std::string held_back = "more like it")
      : period_(period), held_back_(std::move(held_back)) {}

  // `line` under `key` at `now`: the line to say now (with the count held
  // back since the key's last line, if any), or nothing when the key spoke
  // less than a period ago (it is counted for the next line).
  std::optional<std::string> Pass(const std::string& key, const std::string& line,
                                  Clock::time_point now);

 private:
  struct Limit {
    std::optional<Clock::time_point> last;
    uint64_t held_back = 0;
  };
  Clock::duration period_;
  std::string held_back_;
  std::map<std::string, Limit> limits_;
};

}  // namespace simpartner
