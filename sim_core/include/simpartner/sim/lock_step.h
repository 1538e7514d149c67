// The sim's synchronous (lock-step) controllers: who must answer at which
// step, what each answered, and who stalled. No transport: SimNode feeds
// it the decoded SIM_SYNC messages, asks it whether it may take the next
// step, and publishes the replies it returns (sync_t.lcm says the
// protocol). Every refusal names the controller, the tick and why; a
// refused message changes nothing.
//
// Only the controller itself can act for it: its JOINED carries a token
// from a CSPRNG that its DONE and LEAVE marks must carry, and on a signed
// bus they must come from the signing link its JOIN came from (the name
// and sender, which SIM_STATUS publishes, once let any sender leave or
// answer for it). One sender holds at most kMaxControllersPerSender of the
// kMaxControllers places, and a controller released for not answering
// waits before it may join again, twice as long each time.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/command_t.hpp"
#include "simpartner/sync_controller_t.hpp"
#include "simpartner/sync_reply_t.hpp"
#include "simpartner/sync_t.hpp"

namespace simpartner::sim {

// Where a SIM_SYNC message came from: the signing link of a signed bus
// (0 without a key), and when.
struct SyncOrigin {
  uint64_t link = 0;
  std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now();
};

class LockStep {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr int64_t kMaxPeriod = 1000000;
  static constexpr size_t kMaxControllers = 64;
  static constexpr size_t kMaxControllersPerSender = 8;
  // The wait after a first release, doubled with each later one up to the
  // most; an answer after joining again forgets the releases.
  static constexpr std::chrono::seconds kRejoinWaitFirst{5};
  static constexpr std::chrono::seconds kRejoinWaitMost{300};
  // Released names and senders remembered (the longest-free go first).
  static constexpr size_t kMaxReleasesRemembered = 256;
  using Origin = SyncOrigin;

  // What a SIM_SYNC message did: the reply to publish (JOINED, LEFT or
  // REFUSED, none for an accepted DONE), and whether it was refused (for
  // the bad-message count).
  struct Outcome {
    std::optional<sync_reply_t> reply;
    bool refused = false;
  };

  // `step`: the step the sim is at (its state published, the next step
  // not taken). A controller joining at step s answers from the first
  // k >= s with k % period == 0 on; when that is s itself, the caller
  // sends it the state of s (SIM_STATE_REPLY), which it may have missed.
  Outcome Handle(const sync_t& message, int64_t step, const Origin& origin = Origin{});

  // Whether some controller has a tick at `step` (its state must be
  // published, whatever stateEvery says).
  bool IsTick(int64_t step) const;
  // The controllers that must still answer for `step`, by name.
  std::vector<std::string> WaitingOn(int64_t step) const;
  // The commands answered for `step`, in the order of the controllers'
  // names and then as each sent them, with apply_at_step = step (they
  // apply in the step from `step` to step + 1). Call once every
  // controller has answered.
  std::vector<command_t> TakeAnswers(int64_t step);
  // Releases every controller still waited on at `step`: they are no
  // longer synchronous (their later marks are refused, naming the tick,
  // and they may join again only after a wait). Returns a RELEASED reply
  // for each.
  std::vector<sync_reply_t> ReleaseWaiting(int64_t step, const std::string& reason,
                                           Clock::time_point now = Clock::now());
  // Every controller goes (a reset: a new simulation).
  void Clear();

  std::vector<sync_controller_t> Describe(int64_t step) const;
  size_t size() const { return controllers_.size(); }

 private:
  struct Controller {
    std::string sender;
    std::string token;       // its DONE and LEAVE marks carry it
    std::string join_nonce;  // its JOIN's (a repeated JOIN gets the same answer)
    uint64_t link = 0;       // the signing link of its JOIN (0: unsigned bus)
    int64_t period = 1;
    int64_t first_tick = 0;
    int64_t last_done = -1;
    int64_t answered_tick = -1;       // the tick its answer is for
    std::vector<command_t> answer;    // commands of answered_tick, not yet taken
    bool DueAt(int64_t step) const { return step >= first_tick && step % period == 0; }
  };

  // A controller's or a sender's releases: how many, the last tick, and
  // until when it may not join.
  struct Releases {
    int count = 0;
    int64_t tick = -1;
    Clock::time_point not_before;
  };

  Outcome Join(const sync_t& message, int64_t step, const Origin& origin);
  Outcome Leave(const sync_t& message, const Origin& origin);
  Outcome Done(const sync_t& message, int64_t step, const Origin& origin);
  // Why a mark (DONE or LEAVE) may not act for c, or "".
  static std::string NotItsOwn(const sync_t& message, const Controller& c, const Origin& origin);
  // Why message's controller may not join yet (a release's wait), or "".
  std::string StillWaiting(const sync_t& message, Clock::time_point now) const;
  static void Remember(std::map<std::string, Releases>* releases, const std::string& key,
                       int64_t tick, Clock::time_point now);
  static sync_reply_t Reply(const sync_t& message, int8_t event, int64_t period, int64_t tick,
                            std::string reason);
  static Outcome Refuse(const sync_t& message, std::string reason);

  std::map<std::string, Controller> controllers_;  // by name: the answers' order
  std::map<std::string, Releases> released_;          // by controller name
  std::map<std::string, Releases> released_senders_;  // by sender
};

}  // namespace simpartner::sim
