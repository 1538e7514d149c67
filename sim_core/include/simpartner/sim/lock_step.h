// The sim's synchronous (lock-step) controllers: who must answer at which
// step, what each answered, and who stalled. No transport: SimNode feeds
// it the decoded SIM_SYNC messages, asks it whether it may take the next
// step, and publishes the replies it returns (sync_t.lcm says the
// protocol). Every refusal names the controller, the tick and why; a
// refused message changes nothing.
#pragma once

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

class LockStep {
 public:
  static constexpr int64_t kMaxPeriod = 1000000;
  static constexpr size_t kMaxControllers = 64;

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
  Outcome Handle(const sync_t& message, int64_t step);

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
  // longer synchronous (their later marks are refused, naming the tick).
  // Returns a RELEASED reply for each.
  std::vector<sync_reply_t> ReleaseWaiting(int64_t step, const std::string& reason);
  // Every controller goes (a reset: a new simulation).
  void Clear();

  std::vector<sync_controller_t> Describe(int64_t step) const;
  size_t size() const { return controllers_.size(); }

 private:
  struct Controller {
    std::string sender;
    int64_t period = 1;
    int64_t first_tick = 0;
    int64_t last_done = -1;
    int64_t answered_tick = -1;       // the tick its answer is for
    std::vector<command_t> answer;    // commands of answered_tick, not yet taken
    bool DueAt(int64_t step) const { return step >= first_tick && step % period == 0; }
  };

  Outcome Join(const sync_t& message, int64_t step);
  Outcome Leave(const sync_t& message);
  Outcome Done(const sync_t& message, int64_t step);
  static sync_reply_t Reply(const sync_t& message, int8_t event, int64_t period, int64_t tick,
                            std::string reason);
  static Outcome Refuse(const sync_t& message, std::string reason);

  std::map<std::string, Controller> controllers_;  // by name: the answers' order
  std::map<std::string, int64_t> released_;        // name -> the tick it was released at
};

}  // namespace simpartner::sim
