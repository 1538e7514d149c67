// Which simulation a process on the bus follows, and what a SIM_MODEL with
// another simulation id means. Without a key (signed messages) anyone can
// publish a SIM_MODEL: a stale sim on another host, a replayed log, a
// forger. A new id is taken as the followed sim's new simulation only when
//  - it comes from the followed sim's own sender ("program@host:pid", a
//    reset or reload of the same process), or
//  - the followed simulation ended (RUN_STOPPED) or went silent: no
//    SIM_STATE or SIM_STATUS for `silence` (a sim publishes a status at
//    least every statusPeriod, paused too: a restarted sim);
// any other new id is another simulation on the bus. Its model is kept
// aside: if the followed one then ends or goes silent, the newest other
// heard since becomes the followed one (TakeSuccessor), so a sim restarted
// at once after a kill is followed without loss. The logger, the
// sequencer and the viewer share this rule.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>

namespace simpartner {

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

  Verdict OnModel(int64_t id, const std::string& sender, Clock::time_point now);
  // Follows `id` before its model is heard: a client attached to the sim
  // whose SIM_STATUS or SIM_STATE it heard first, or to the one it was
  // told. The first SIM_MODEL of `id` names its sender.
  void Attach(int64_t id, Clock::time_point now);
  // A SIM_STATE or SIM_STATUS of `id` came.
  void Heard(int64_t id, Clock::time_point now);
  // The followed simulation said RUN_STOPPED (or was closed as silent).
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
  struct Other {
    std::string sender;
    Clock::time_point heard;
  };
  bool FollowedIsGone(Clock::time_point now) const;
  void Follow(int64_t id, const std::string& sender, Clock::time_point now);

  Clock::duration silence_;
  int64_t followed_ = 0;
  std::optional<std::string> followed_sender_;  // nothing while attached without a model
  Clock::time_point followed_heard_{};
  bool followed_ended_ = false;
  std::set<int64_t> followed_before_;
  std::map<int64_t, Other> others_;
};

}  // namespace simpartner
