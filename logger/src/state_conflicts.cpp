#include "simpartner/logger/state_conflicts.h"

#include <functional>
#include <string_view>

namespace simpartner::logger {
namespace {

// An encoded state_t: the type's 8-byte fingerprint, then utime (int64),
// then the rest (lcmtypes/state_t.lcm).
constexpr size_t kUtimeEnd = 16;

}  // namespace

uint64_t StateConflicts::Fingerprint(const std::vector<uint8_t>& message) {
  const size_t skip = message.size() >= kUtimeEnd ? kUtimeEnd : 0;
  const std::string_view rest(reinterpret_cast<const char*>(message.data()) + skip,
                              message.size() - skip);
  return std::hash<std::string_view>{}(rest);
}

std::optional<uint64_t> StateConflicts::Remember(int64_t simulation, int64_t step,
                                                 uint64_t fingerprint) {
  Steps& steps = simulations_[simulation];
  steps.last_use = ++uses_;
  if (simulations_.size() > kSimulations) {
    auto oldest = simulations_.begin();
    for (auto it = simulations_.begin(); it != simulations_.end(); ++it)
      if (it->second.last_use < oldest->second.last_use) oldest = it;
    simulations_.erase(oldest);  // never `steps`: it was used last
  }
  const auto [it, is_new] = steps.fingerprints.emplace(step, fingerprint);
  if (!is_new) return it->second;
  if (steps.fingerprints.size() > kStepsPerSimulation)
    steps.fingerprints.erase(steps.fingerprints.begin());  // the lowest step
  return std::nullopt;
}

StateConflicts::Verdict StateConflicts::Check(int64_t simulation, int64_t step,
                                              const std::vector<uint8_t>& message,
                                              Clock::time_point now) {
  const uint64_t fingerprint = Fingerprint(message);
  const std::optional<uint64_t> before = Remember(simulation, step, fingerprint);
  Verdict verdict;
  if (!before || *before == fingerprint) return verdict;
  verdict.conflict = true;
  ++count_;
  verdict.line = lines_.Pass(
      "conflict",
      "bus simulation " + std::to_string(simulation) + ", step " + std::to_string(step) +
          ": two different SIM_STATEs for one step: another sender on the bus forges this "
          "simulation's states; the first was kept; on a signed bus (the default, not "
          "SIMPARTNER_BUS_KEY=none) forged states are refused (docs/security.md); " +
          std::to_string(count_) + " conflicting states so far",
      now);
  return verdict;
}

}  // namespace simpartner::logger
