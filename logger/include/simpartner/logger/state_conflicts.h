// Two different SIM_STATEs for one step of one simulation. Without a bus
// key a forger can send a state for a step the sim has not reached yet,
// within the step allowance (receiver.h): it is logged, and the real state
// of that step, coming later, is kept out as a duplicate. Which of the two
// is real cannot be told without a signature, but that there are two is
// seen: each accepted state's fingerprint is remembered, and a later state
// of the same step with another fingerprint is a conflict, counted and
// named at most once a second. An identical state (a retransmit, a second
// path to the same sim) is not a conflict.
//
// Memory is bounded: per simulation the highest kStepsPerSimulation steps
// (the lowest go first, so a forged state far ahead stays remembered until
// the real one of its step comes), for the kSimulations simulations last
// seen: at most 16,384 fingerprints, about 1 MiB with the maps' nodes.
// Not thread-safe: the receive thread owns it.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/rate_limited_log.h"

namespace simpartner::logger {

class StateConflicts {
 public:
  using Clock = RateLimitedLog::Clock;
  static constexpr size_t kStepsPerSimulation = 4096;
  static constexpr size_t kSimulations = 4;
  static constexpr Clock::duration kReportPeriod = std::chrono::seconds(1);

  struct Verdict {
    bool conflict = false;            // another state of this step came before, different
    std::optional<std::string> line;  // what to say now (at most one a kReportPeriod)
  };

  // An accepted state of `simulation` at `step`; `message` is its encoded
  // state_t (without a signature).
  Verdict Check(int64_t simulation, int64_t step, const std::vector<uint8_t>& message,
                Clock::time_point now);
  uint64_t count() const { return count_; }

  // A 64-bit hash of an encoded state_t without its utime (the time it
  // was published, which a resend may change). Not cryptographic: it tells
  // two states apart, it does not authenticate either (that is the key's
  // job).
  static uint64_t Fingerprint(const std::vector<uint8_t>& message);

 private:
  struct Steps {
    std::map<int64_t, uint64_t> fingerprints;  // by step
    uint64_t last_use = 0;
  };
  // Remembers `fingerprint` for the step unless one is there; returns the
  // one that was there.
  std::optional<uint64_t> Remember(int64_t simulation, int64_t step, uint64_t fingerprint);

  std::map<int64_t, Steps> simulations_;  // by simulation id
  uint64_t uses_ = 0;
  uint64_t count_ = 0;
  RateLimitedLog lines_{kReportPeriod, "more conflicting states"};
};

}  // namespace simpartner::logger
