// What a batch run's bus shows: the model (for the bodies' indices), every
// SIM_STATE hashed in step order (wall clock and simulation id left out:
// they differ from run to run), and the figures of the batch file.
//
// It also paces the sim: it joins as a synchronous (lock-step) controller
// with a period of kPacePeriod steps and answers each tick, with no
// commands, once it has that tick's state. So the sim is never more than
// a period ahead of what this process has read, and a logger beside it
// sees the same pace: on a loaded machine (a Slurm node running several
// tasks) a run takes longer, but no state is lost in a full socket
// buffer. The answers change nothing in the run (sync_t.lcm).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/batch/batch_file.h"
#include "simpartner/bus_decode.h"
#include "simpartner/message_checks.h"
#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/sync_reply_t.hpp"

namespace simpartner::batch {

class RunObserver {
 public:
  static constexpr int64_t kPacePeriod = 50;  // [steps]
  // Its lock-step name (controllers' names order their commands; it sends none).
  static constexpr const char* kPaceName = "simpartner-batch";

  // Opens `url` (throws std::runtime_error when LCM cannot).
  RunObserver(const std::string& url, const std::vector<Figure>& figures);
  // Handles what arrives until nothing has for `quiet_ms`, or for
  // `budget_ms` at most (states keep coming while a sim runs). Throws
  // std::runtime_error when LCM cannot receive at all.
  void Pump(int quiet_ms, int budget_ms = 100);

  // Asks the sim to take this observer as a lock-step controller (call
  // again until joined(): a datagram may be lost). The sim should be
  // paused, so that no step goes unpaced.
  void AskToJoin();
  bool joined() const { return first_tick_ >= 0; }
  // Why the sim refused the join or released the observer, or "".
  const std::string& pace_problem() const { return pace_problem_; }

  int64_t states() const { return states_; }
  int64_t last_step() const { return last_step_; }
  double sim_time() const { return sim_time_; }
  // 16 hex digits; "" when a state was missed (a step skipped, or the
  // stream ended before `last_step`).
  std::string Hash(int64_t last_step) const;
  // The model's step size [s], 0 before the model.
  double step_size() const { return model_ ? model_->step_size : 0.0; }
  // In the figures' order; NaN for a body the model lacks or no state.
  std::vector<double> Figures() const;

 private:
  struct Accumulator {
    int body = -1;
    bool any = false;
    double position[3] = {0, 0, 0}, speed = 0, path = 0, peak_force = 0;
  };
  void OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnStateReply(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnSyncReply(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  // A SIM_SYNC mark of this observer: JOIN with its period, DONE for a tick.
  void PublishMark(int8_t action, int64_t period, int64_t tick);
  void Answer(int64_t tick);
  void AskAgainIfQuiet();
  void Accumulate(const state_t& state);

  BusSigning* signer() { return signing_ ? &*signing_ : nullptr; }

  lcm::LCM lcm_;
  std::string url_;
  std::optional<BusSigning> signing_;  // SIMPARTNER_BUS_KEY, as its sims have
  std::vector<Figure> figures_;
  std::vector<Accumulator> accumulators_;
  std::optional<model_t> model_;
  ModelOutline outline_;  // of model_: what its states must fit
  BadMessageCounter refused_;
  uint64_t hash_ = 1469598103934665603ull;  // FNV-1a offset basis
  bool complete_ = true;
  int64_t states_ = 0, last_step_ = -1;
  double sim_time_ = 0;
  // Pacing: ticks are multiples of kPacePeriod from first_tick_ on.
  std::string sender_;
  // Its JOIN's nonce and the token JOINED gave (sync_t.lcm).
  std::string join_nonce_, token_;
  int64_t first_tick_ = -1, answered_ = -1;
  bool pacing_ = true;  // false once refused or released
  std::string pace_problem_;
  std::chrono::steady_clock::time_point last_heard_ = std::chrono::steady_clock::now();
};

}  // namespace simpartner::batch
