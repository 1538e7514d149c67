// The receive side of the logger: decodes (through simpartner::DecodeLcm,
// common/include/simpartner/bus_decode.h) and checks every message on its
// channels, learns each simulation's model from SIM_MODEL (asking for it
// with SIM_MODEL_REQUEST while messages of an unknown simulation wait), and
// hands good records to the queue. It never waits for the database. A
// message that does not decode, has bytes left over, or does not fit the
// model (counts, indices, non-finite numbers, text the database cannot
// store, a step number beyond what the sim's rate allows) is counted per
// channel, reported, and never written. Steps the queue could not keep (its
// spool disk full) are recorded as a gap with that reason; a simulation
// whose sim goes silent is closed, and reopened if the sim is heard again
// (it was stopped, or its link was down), with the silence as a gap.
// It logs the simulation it follows (common/.../simulation_follower.h): a
// SIM_MODEL of another simulation (a second sim on the bus, a stale or
// forged one) closes nothing and is not logged, unless the followed sim
// stops or goes silent first, as a restarted sim's does.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "simpartner/bus_decode.h"
#include "simpartner/message_checks.h"
#include "simpartner/bus_signing.h"
#include "simpartner/logger/record_queue.h"
#include "simpartner/logger/reporter.h"
#include "simpartner/logger/state_conflicts.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/simulation_follower.h"
#include "simpartner/state_t.hpp"

namespace simpartner::logger {

struct ReceiverOptions {
  int log_interval = 1;           // keep states whose step is a multiple of this
  std::string sender;             // sender name in SIM_MODEL_REQUEST
  uint64_t max_waiting_bytes = 64u << 20;  // messages waiting for their model
  // A simulation with no SIM_STATE or SIM_STATUS for this long (and no
  // RUN_STOPPED) is closed: its sim died, as far as anyone can tell. If
  // the sim is heard again it is reopened. [s]
  double sim_silence = 10.0;
  // A new simulation from another sender is followed (logged) once the
  // followed sim has not been heard for this long (a restarted sim; the sim
  // publishes a status at least every second by default) or stopped;
  // before, it is another simulation on the bus. [s]
  double follow_silence = 2.5;
  // With a key (bus_signing.h; outlives the receiver): only signed, fresh
  // messages; null: an unsigned bus.
  BusSigning* signing = nullptr;
  // Records other than states that the queue refused (its spool disk
  // full), held in memory until it takes them again.
  uint64_t max_held_bytes = 8u << 20;
};

// The step-number rule: a state may be at most `factor` times real time
// ahead of the last one of its simulation, counted from the wall time
// between their arrivals plus kStepAllowanceMarginSeconds (so a burst, a
// pause or a slow receive loop never trips it; a forged leap does). The
// factor comes from the sim's own SIM_STATUS (SpeedAllowance), and is
// kStepAllowanceFactor until its first status.
inline constexpr double kStepAllowanceFactor = 1000.0;
inline constexpr double kStepAllowanceMarginSeconds = 1.0;
// Steps a state may be ahead of the previous one (step_size [s], elapsed
// wall time [us]).
int64_t StepAllowance(double step_size, int64_t elapsed_us,
                      double factor = kStepAllowanceFactor);
// The factor for a sim whose status says target_speed (<= 0: as fast as
// possible) and real_time_factor (measured over its last status period):
// twice the target or the measured rate, at least 2; as fast as possible,
// four times the measured rate, at least 10, and kStepAllowanceFactor
// while it has measured nothing (paused, starting).
double SpeedAllowance(double target_speed, double real_time_factor);

struct ChannelCounts {
  uint64_t received = 0;
  uint64_t malformed = 0;  // did not decode as the channel's type (foreign, truncated, padded)
  uint64_t invalid = 0;    // decoded but does not fit the model or the database
  uint64_t unsigned_or_forged = 0;  // with a key: no valid, fresh signature
};

struct ReceiverStats {
  std::map<std::string, ChannelCounts> channels;
  uint64_t states_queued = 0;
  uint64_t states_skipped = 0;     // between logged steps (logEveryStep=0)
  uint64_t waiting = 0;            // messages waiting for their simulation's model
  uint64_t dropped_no_model = 0;   // waited too long (more than max_waiting_bytes)
  uint64_t lost_spool_failed = 0;  // neither memory nor disk could take them
  uint64_t lost_spool_bytes = 0;
  uint64_t lost_states = 0;        // of which states (recorded in LogGap)
  uint64_t held = 0;               // other records refused, held in memory to be queued later
  uint64_t simulations_silent = 0; // closed because their sim went silent (and not heard since)
  uint64_t simulations_reopened = 0;  // closed as silent, then heard again
  uint64_t model_requests = 0;
  uint64_t other_simulations = 0;  // other simulation ids heard on the bus, not logged
  uint64_t state_conflicts = 0;    // two different SIM_STATEs for one step (state_conflicts.h)
  int64_t simulation_id = 0;       // the simulation followed (latest model)
  int64_t last_step = -1;          // its last state received
  int64_t last_publish_us = 0;     // and when the sim published it
  // The newest publish stamp of the followed simulation's SIM_STATE or
  // SIM_STATUS (sender's wall clock) [us].
  int64_t newest_stamp_us = 0;
  bool followed_ended = false;     // it said RUN_STOPPED or was closed as silent
  uint64_t BadMessages() const;
};

// What a simulation's other messages must fit (CheckState and
// CheckSensorReading, message_checks.h) and its step timing.
struct ModelShape {
  ModelOutline outline;
  int32_t state_every = 1;
  double step_size = 0.001;  // [s]
};

ModelShape ShapeOf(const model_t& model);

class Receiver {
 public:
  // lcm, queue and reporter outlive the receiver. Subscribes at once.
  Receiver(lcm::LCM* lcm, RecordQueue* queue, ReceiverOptions options, Reporter* reporter);
  Receiver(const Receiver&) = delete;
  Receiver& operator=(const Receiver&) = delete;

  // Asks the sim for SIM_MODEL now.
  void RequestModel();
  // Housekeeping between messages: asks for SIM_MODEL (at most 4 times a
  // second) while messages wait for one; records steps the spool refused
  // once it takes records again; closes simulations whose sim went silent.
  void Tick();
  ReceiverStats Stats() const;

 private:
  void OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnSensor(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnCommand(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnReply(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnStatus(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  // Decodes into message; counts and reports if it does not decode exactly.
  template <class Message>
  bool Decode(const lcm::ReceiveBuffer* buffer, const std::string& channel, Message* message);
  void Invalid(const std::string& channel, const std::string& problem);
  // The message's size without its signature (OpenMessage); with a key,
  // nothing when it is not signed and fresh (counted and reported).
  std::optional<size_t> OpenSigned(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  // The step-number rule for a state that fits its model; "" if it passes.
  std::string CheckStepRate(const state_t& state, int64_t received_us, const ModelShape& shape);
  // Counts and names (at most once a second) a state whose step came
  // before with other contents; the record goes on as before (the first of
  // a step is the one kept).
  void CheckConflict(const state_t& state, const Record& record);
  Record MakeRecord(RecordKind kind, int64_t simulation_id, const lcm::ReceiveBuffer* buffer) const;
  // To the queue, or to the waiting list if the model is not known yet.
  // `decoded`: the state in the record, if the caller has decoded it.
  void Deliver(Record record, const state_t* decoded = nullptr);
  // `step`: the state's step for a state record (for the gap if it is
  // refused), else -1.
  void Push(Record record, int64_t step = -1);
  // Queues what the queue refused before (gap records for states, the
  // other records themselves), oldest first; false if it still refuses.
  bool PushPending();
  // Says once that the queue takes records again after refusing some.
  void SpoolRecovered();
  void CloseSilent();
  // `simulation` said RUN_STOPPED or was closed as silent.
  void MarkEnded(int64_t simulation);
  // The sim of a simulation with a model spoke (SIM_STATE or SIM_STATUS):
  // reopens the simulation if it was closed as silent.
  void Heard(int64_t simulation);
  // After a reopening: the silence as a gap, from the last step before it
  // to `state`, the first after.
  void PushSilenceGap(const state_t& state, const ModelShape& shape);
  void Wait(Record record);
  // A model of another simulation than the followed one: kept, not logged.
  void SetAside(const model_t& model, Record record);
  // `simulation` is followed: its model to the queue, then what waited.
  void Follow(int64_t simulation, const ModelShape& shape, Record model_record);
  void DeliverWaiting(int64_t simulation);
  // Follows the newest other simulation once the followed one is gone.
  void FollowSuccessor();
  // Some waiting message belongs to a simulation whose model is unknown.
  bool NeedsModel() const;

  struct SetAsideModel {
    ModelShape shape;
    Record record;
    std::optional<int64_t> stopped_at;  // its sim said RUN_STOPPED at this step
  };
  static constexpr size_t kMaxSetAside = 8;

  // Per simulation: the newest state accepted and when it came (for the
  // step-number rule), and when the sim was last heard of (for silence).
  struct SimClock {
    int64_t step = -1;
    int64_t received_us = 0;
    double speed_allowance = kStepAllowanceFactor;  // from its SIM_STATUS
    std::chrono::steady_clock::time_point heard{};
    bool closed_silent = false;
    // Reopened after a silence: its last step before it, and how long it
    // lasted, until the next state gives the end of the gap.
    int64_t silence_after_step = -1;
    double silence_seconds = 0;
  };
  // What the queue refused, in order: a run of states of one simulation
  // (first..last, how many: queued later as a gap record), or another
  // record (a model, an end of simulation, a command...) held in memory.
  struct Pending {
    bool is_gap = false;
    Record record;
    int64_t first = 0;
    int64_t last = 0;
    int64_t count = 0;
    std::string cause;
  };

  lcm::LCM* lcm_;
  RecordQueue* queue_;
  ReceiverOptions options_;
  Reporter* reporter_;
  SimulationFollower follower_;
  std::map<int64_t, SetAsideModel> set_aside_;  // by simulation id
  std::map<int64_t, ModelShape> models_;  // by simulation id (followed, now or before)
  std::set<int64_t> ended_;
  std::map<int64_t, SimClock> clocks_;   // by simulation id
  std::deque<Pending> pending_;
  uint64_t pending_bytes_ = 0;
  bool spool_failing_ = false;
  std::string last_spool_cause_;
  std::deque<Record> waiting_;
  uint64_t waiting_bytes_ = 0;
  std::chrono::steady_clock::time_point last_request_{};
  std::chrono::steady_clock::time_point last_waiting_check_{};  // Tick's NeedsModel
  StateConflicts conflicts_;
  mutable std::mutex stats_mutex_;
  BadMessageCounter signature_refusals_;  // for its lines (guarded by stats_mutex_)
  ReceiverStats stats_;
};

}  // namespace simpartner::logger
