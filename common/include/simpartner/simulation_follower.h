// Which simulation a process on the bus follows, and what a SIM_MODEL with
// another simulation id means. Without a key (signed messages) anyone can
// publish a SIM_MODEL: a stale sim on another host, a replayed log, a
// forger, or a copy of the followed sim's own model, sender and all. A
// new id is taken as the followed sim's new simulation only when the
// followed simulation said it ended (RUN_STOPPED: it quit; RUN_RESET: it
// was reset, and its successor's model follows) or went silent: no
// SIM_STATE or SIM_STATUS for `silence` (a sim publishes a status at
// least every statusPeriod, paused too: a restarted sim). While it still
// publishes, any other new id is another simulation on the bus. Its model
// is kept aside: if the followed one then ends or goes silent, the other
// whose states or status came last, within `silence`, becomes the followed
// one (TakeSuccessor), so a sim restarted at once after a kill is followed
// without loss, and a copied model with nothing behind it never is. The
// logger, the sequencer and the viewer share this rule.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>

namespace simpartner {

// A status saying its simulation is over: RUN_STOPPED or RUN_RESET.
bool EndsSimulation(int8_t run_state);

class SimulationFollower {
 public:
  using Clock = std::chrono::steady_clock;
  // At most this many other simulations are remembered (the ones heard
  // longest ago are forgotten): forged ids come without end.
  static constexpr size_t kMaxOthers = 64;

  enum class Verdict {
    kFollow,   // it is now the followed simulation (the first, a reset, a restart)
    kKnown,    // the followed one, or one followed before, announced again
    kOther,    // another simulation on the bus: not followed (named once by the caller)
  };

  explicit SimulationFollower(Clock::duration silence = std::chrono::milliseconds(2500))
      : silence_(silence) {}

  Verdict OnModel(int64_t id, Clock::time_point now);
  // Follows `id` before its model is heard: a client attached to the sim
  // whose SIM_STATUS or SIM_STATE it heard first, or to the one it was
  // told.
  void Attach(int64_t id, Clock::time_point now);
  // A SIM_STATE or SIM_STATUS of `id` came.
  void Heard(int64_t id, Clock::time_point now);
  // The followed simulation is over: its status said so (EndsSimulation),
  // or it was closed as silent.
  void Ended(int64_t id);
  // When the followed simulation ended or went silent and another was
  // heard since: that one (the newest), now followed; else nullopt.
  std::optional<int64_t> TakeSuccessor(Clock::time_point now);

  // 0 before any model (or Attach).
  int64_t followed() const { return followed_; }
  // The followed simulation or one followed before (its late messages
  // still belong to it).
  bool WasFollowed(int64_t id) const { return id != 0 && followed_before_.count(id) > 0; }
  bool IsOther(int64_t id) const { return others_.count(id) > 0; }

 private:
  bool FollowedIsGone(Clock::time_point now) const;
  void Follow(int64_t id, Clock::time_point now);

  Clock::duration silence_;
  int64_t followed_ = 0;
  Clock::time_point followed_heard_{};
  bool followed_ended_ = false;
  std::set<int64_t> followed_before_;
  // When each last sent a state or status (never: the epoch).
  std::map<int64_t, Clock::time_point> others_;
};

}  // namespace simpartner
