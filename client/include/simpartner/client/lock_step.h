// Lock-step: control code in the loop, synchronous with the sim, so that a
// closed loop repeats bit for bit at any speed and on any machine.
//
//   Client sim;                                  // a sim started paused
//   LockStepOptions options;
//   options.period = 10;                         // a tick every 10 steps
//   LockStep loop(sim, options);                 // joins, resumes the sim
//   for (int i = 0; i < 1000; ++i) {
//     const state_t& s = loop.Next();            // the state of tick k
//     sim.Send(SetVelocity(sim.Find("Axle1Motor"), {Decide(s)}));
//   }                                            // leaves when destroyed
//
// Next() answers the previous tick with the commands Send queued since
// (they apply in the step after that tick), then waits for the state of
// the next tick: the sim takes no step past a tick until every
// synchronous controller has answered it (sync_t.lcm). A tick's state
// lost on the way is asked for again (SIM_STATE_REQUEST), and an answer
// the sim still waits for is sent again (the sim refuses and counts it as
// a duplicate if the first had come), so a lost datagram on a busy
// machine costs time, not the run.
#pragma once

#include <cstdint>
#include <string>

#include "simpartner/client/client.h"

namespace simpartner::client {

struct LockStepOptions {
  int64_t period = 1;       // [steps] between ticks, 1 to 1000000
  std::string name;         // unique among the sim's controllers; "" = the
                            // client's program name
  bool resume = true;       // resume a paused sim once joined
  double timeout = 10.0;    // [s] wait for a tick's state (or a join) before Timeout
};

class LockStep {
 public:
  // Joins (asking again until the sim answers): throws LockStepError when
  // the sim refuses (a name in use, a bad period), Timeout, SimRestarted.
  LockStep(Client& client, LockStepOptions options = {});
  // Leaves: the sim stops waiting for this controller. Never throws.
  ~LockStep();
  LockStep(const LockStep&) = delete;
  LockStep& operator=(const LockStep&) = delete;

  // The state of the next tick (the first call: the tick the sim named at
  // the join). Throws Refused when the sim refused a command of the
  // previous tick, LockStepError when it released this controller (it was
  // too slow: lockStepTimeout) or refused its answer, SimStopped when the
  // sim ended (its duration reached: the loop's normal end in a batch),
  // Timeout, SimRestarted.
  const state_t& Next();

  int64_t tick() const { return tick_; }  // of the last Next(), -1 before
  int64_t first_tick() const { return first_tick_; }
  int64_t period() const { return options_.period; }
  const std::string& name() const { return options_.name; }
  // State requests and answers sent again for ticks that were late.
  int64_t resends() const { return resends_; }

 private:
  void Join();
  void ResumeIfPaused();
  void SendAnswer(int64_t next_tick);
  state_t AwaitTick(int64_t tick);
  // Whether a SIM_SYNC_REPLY in this controller's name answers its own
  // marks (sync_reply_t.token), not another sender's.
  bool AboutOwnMark(const sync_reply_t& reply) const;
  void CheckSyncReplies(int64_t tick);
  void CheckPreviousReplies();

  Client& client_;
  LockStepOptions options_;
  // What only this controller holds (sync_t.lcm): its JOIN's nonce, and
  // the token the sim's JOINED gave, which its DONE and LEAVE carry.
  std::string join_nonce_;
  std::string token_;
  int64_t first_tick_ = -1;
  int64_t tick_ = -1;
  state_t state_;
  sync_t answer_;                   // the last answer sent
  std::vector<int64_t> answered_;   // request ids of its commands
  int64_t resends_ = 0;
};

}  // namespace simpartner::client
