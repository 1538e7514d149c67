#include "simpartner/logger/receiver.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "simpartner/bus_decode.h"
#include "simpartner/channels.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/message_checks.h"
#include "simpartner/model_request_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/text.h"
#include "simpartner/sender.h"

namespace simpartner::logger {
namespace {

constexpr auto kModelRequestPeriod = std::chrono::milliseconds(250);

}  // namespace

uint64_t ReceiverStats::BadMessages() const {
  uint64_t n = 0;
  for (const auto& [channel, c] : channels) n += c.malformed + c.invalid + c.unsigned_or_forged;
  return n;
}

ModelShape ShapeOf(const model_t& model) {
  return ModelShape{OutlineOf(model), std::max(1, model.state_every), model.step_size};
}

int64_t StepAllowance(double step_size, int64_t elapsed_us, double factor) {
  const double seconds = static_cast<double>(std::max<int64_t>(0, elapsed_us)) / 1e6 +
                         kStepAllowanceMarginSeconds;
  const double steps = std::ceil(factor * seconds / step_size);
  return steps >= 9e18 ? INT64_MAX : static_cast<int64_t>(steps);
}

double SpeedAllowance(double target_speed, double real_time_factor) {
  const double measured = std::isfinite(real_time_factor) ? std::max(0.0, real_time_factor) : 0.0;
  if (std::isfinite(target_speed) && target_speed > 0)
    return std::min(kStepAllowanceFactor, std::max({2.0, 2 * target_speed, 2 * measured}));
  if (measured <= 0) return kStepAllowanceFactor;
  return std::min(kStepAllowanceFactor, std::max(10.0, 4 * measured));
}

Receiver::Receiver(lcm::LCM* lcm, RecordQueue* queue, ReceiverOptions options, Reporter* reporter)
    : lcm_(lcm),
      queue_(queue),
      options_(std::move(options)),
      reporter_(reporter),
      follower_(std::chrono::duration_cast<SimulationFollower::Clock::duration>(
          std::chrono::duration<double>(options_.follow_silence))) {
  // Every message counts: deep subscription queues (the socket buffer is
  // raised in the URL).
  lcm_->subscribe(channels::kModel, &Receiver::OnModel, this)->setQueueCapacity(1000);
  lcm_->subscribe(channels::kState, &Receiver::OnState, this)->setQueueCapacity(100000);
  lcm_->subscribe(channels::kSensor, &Receiver::OnSensor, this)->setQueueCapacity(100000);
  lcm_->subscribe(channels::kCommand, &Receiver::OnCommand, this)->setQueueCapacity(10000);
  lcm_->subscribe(channels::kCommandReply, &Receiver::OnReply, this)->setQueueCapacity(10000);
  lcm_->subscribe(channels::kStatus, &Receiver::OnStatus, this)->setQueueCapacity(1000);
}

template <class Message>
bool Receiver::Decode(const lcm::ReceiveBuffer* buffer, const std::string& channel,
                      Message* message) {
  const std::optional<size_t> size = OpenSigned(buffer, channel);
  if (!size) return false;
  const std::optional<DecodeFailure> failure = DecodeLcm(buffer->data, *size, message);
  uint64_t count = 0;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ChannelCounts& c = stats_.channels[channel];
    ++c.received;
    if (failure) count = ++c.malformed;
  }
  if (!failure) return true;
  reporter_->SayLimited(channel + "/malformed",
                        DescribeRefusal(channel, Message::getTypeName(), *size, *failure) +
                            "; not written (" + std::to_string(count) + " malformed so far)");
  return false;
}

std::optional<size_t> Receiver::OpenSigned(const lcm::ReceiveBuffer* buffer,
                                           const std::string& channel) {
  const BusSigning::Opened opened = OpenMessage(options_.signing, channel, buffer->data,
                                                static_cast<size_t>(buffer->data_size));
  if (opened.refusal.empty()) return opened.size;
  std::optional<std::string> line;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ChannelCounts& c = stats_.channels[channel];
    ++c.received;
    ++c.unsigned_or_forged;
    // At most a line a second for all channels, with the count since the last.
    line = signature_refusals_.CountSignatureRefusal(
        channel,
        DescribeSignatureRefusal(channel, static_cast<size_t>(buffer->data_size), opened.refusal),
        Reporter::Clock::now());
  }
  if (line) reporter_->Say(*line + "; not written");
  return std::nullopt;
}

void Receiver::Invalid(const std::string& channel, const std::string& problem) {
  uint64_t count = 0;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    count = ++stats_.channels[channel].invalid;
  }
  reporter_->SayLimited(channel + "/invalid", channel + ": " + problem + "; not written (" +
                                                 std::to_string(count) + " invalid so far)");
}

Record Receiver::MakeRecord(RecordKind kind, int64_t simulation_id,
                            const lcm::ReceiveBuffer* buffer) const {
  Record r;
  r.kind = kind;
  r.simulation_id = simulation_id;
  r.received_us = WallMicros();
  // The message without its signature (checked in Decode).
  const uint8_t* data = static_cast<const uint8_t*>(buffer->data);
  r.payload.assign(data, data + UnsignedSize(data, static_cast<size_t>(buffer->data_size)));
  return r;
}

void Receiver::Push(Record record, int64_t step) {
  const bool is_state = record.kind == RecordKind::kState;
  const uint64_t bytes = record.ByteSize();
  std::string cause;
  // What was refused before goes first, so the writer meets a gap where
  // its steps would have been and a held record where it came.
  if (PushPending()) {
    try {
      queue_->Push(std::move(record));  // left as it was if refused
      if (is_state) {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.states_queued;
      }
      SpoolRecovered();
      return;
    } catch (const SpoolError& e) {
      cause = e.what();
    }
  }
  if (!cause.empty()) last_spool_cause_ = cause;
  spool_failing_ = true;
  if (!is_state || step < 0) {
    // Few and small (models, ends of simulations, commands): held in
    // memory until the queue takes them, up to a bound.
    if (pending_bytes_ + bytes <= options_.max_held_bytes) {
      pending_bytes_ += bytes;
      Pending held;
      held.record = std::move(record);
      pending_.push_back(std::move(held));
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.held;
      return;
    }
  } else {
    const int64_t simulation = record.simulation_id;
    if (pending_.empty() || !pending_.back().is_gap ||
        pending_.back().record.simulation_id != simulation) {
      Pending gap;
      gap.is_gap = true;
      gap.record.simulation_id = simulation;
      gap.first = gap.last = step;
      pending_.push_back(std::move(gap));
    }
    Pending& gap = pending_.back();
    gap.first = std::min(gap.first, step);
    gap.last = std::max(gap.last, step);
    ++gap.count;
    if (!cause.empty()) gap.cause = cause;
  }
  uint64_t lost_records = 0, lost_bytes = 0, lost_states = 0;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    lost_records = ++stats_.lost_spool_failed;
    lost_bytes = (stats_.lost_spool_bytes += bytes);
    if (is_state) ++stats_.lost_states;
    lost_states = stats_.lost_states;
  }
  const QueueStats q = queue_->Stats();
  char text[320];
  std::snprintf(text, sizeof text,
                "cannot keep a record: the memory queue is full and the spool disk refuses it; "
                "kept %.1f MB in memory and %.1f MB in the spool, refused %llu records (%.1f MB, "
                "%llu steps) so far",
                static_cast<double>(q.memory_bytes) / 1e6,
                static_cast<double>(q.spool_stored_bytes) / 1e6,
                static_cast<unsigned long long>(lost_records), static_cast<double>(lost_bytes) / 1e6,
                static_cast<unsigned long long>(lost_states));
  reporter_->SayLimited("spool", std::string(text) + " (" + last_spool_cause_ +
                                     "); the steps refused go into LogGap");
}

bool Receiver::PushPending() {
  while (!pending_.empty()) {
    Pending& p = pending_.front();
    try {
      if (p.is_gap) {
        GapPayload gap{p.first, p.last, p.count,
                       "refused by the logger: memory queue full and spool disk full" +
                           (p.cause.empty() ? std::string() : " (" + p.cause + ")")};
        queue_->Push(MakeGapRecord(p.record.simulation_id, WallMicros(), gap));
      } else {
        const uint64_t bytes = p.record.ByteSize();
        queue_->Push(std::move(p.record));
        pending_bytes_ -= bytes;
      }
    } catch (const SpoolError&) {
      return false;
    }
    pending_.pop_front();
  }
  return true;
}

void Receiver::SpoolRecovered() {
  if (!spool_failing_) return;
  spool_failing_ = false;
  const ReceiverStats s = Stats();
  reporter_->Say("the spool takes records again; " + std::to_string(s.lost_spool_failed) +
                 " records (" + std::to_string(s.lost_states) +
                 " steps) were refused while it was full, the steps recorded in LogGap");
}

void Receiver::Wait(Record record) {
  const bool set_aside = set_aside_.count(record.simulation_id) > 0;
  waiting_bytes_ += record.ByteSize();
  waiting_.push_back(std::move(record));
  uint64_t dropped = 0;
  while (waiting_bytes_ > options_.max_waiting_bytes && !waiting_.empty()) {
    waiting_bytes_ -= waiting_.front().ByteSize();
    waiting_.pop_front();
    ++dropped;
  }
  uint64_t dropped_total = 0;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.waiting = waiting_.size();
    stats_.dropped_no_model += dropped;
    dropped_total = stats_.dropped_no_model;
  }
  if (dropped > 0)
    reporter_->SayLimited("no model",
                          "messages waiting for their SIM_MODEL, or of another simulation "
                          "waiting to be followed, beyond " +
                              std::to_string(options_.max_waiting_bytes >> 20) +
                              " MiB: dropped " + std::to_string(dropped_total) +
                              " so far (does the sim answer SIM_MODEL_REQUEST? is a second sim "
                              "on this bus?)");
  if (!set_aside && std::chrono::steady_clock::now() - last_request_ > kModelRequestPeriod)
    RequestModel();
}

void Receiver::RequestModel() {
  model_request_t request;
  request.utime = WallMicros();
  request.sender = options_.sender;
  PublishSigned(lcm_, channels::kModelRequest, request, options_.signing);
  last_request_ = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(stats_mutex_);
  ++stats_.model_requests;
}

void Receiver::Tick() {
  // Tick runs after every message; what waits (up to 64 MiB of records) is
  // looked through at most once a request period.
  const auto now = std::chrono::steady_clock::now();
  if (!waiting_.empty() && now - last_request_ > kModelRequestPeriod &&
      now - last_waiting_check_ > kModelRequestPeriod) {
    last_waiting_check_ = now;
    if (NeedsModel()) RequestModel();
  }
  if (!pending_.empty() && PushPending()) SpoolRecovered();
  CloseSilent();
  FollowSuccessor();
}

bool Receiver::NeedsModel() const {
  // Messages of a simulation set aside wait for it to be followed, not for
  // a model.
  return std::any_of(waiting_.begin(), waiting_.end(),
                     [&](const Record& r) { return set_aside_.count(r.simulation_id) == 0; });
}

void Receiver::FollowSuccessor() {
  const auto next = follower_.TakeSuccessor(std::chrono::steady_clock::now());
  if (!next) return;
  reporter_->Say("following simulation " + std::to_string(*next) +
                 ": the one before stopped or went silent (a restarted sim)");
  const auto aside = set_aside_.find(*next);
  if (aside == set_aside_.end()) {
    RequestModel();  // followed from its model, when it comes
    return;
  }
  SetAsideModel model = std::move(aside->second);
  set_aside_.erase(aside);
  Follow(*next, model.shape, std::move(model.record));
  if (model.stopped_at) {  // it ran and stopped while set aside
    MarkEnded(*next);
    Push(MakeEndedRecord(*next, WallMicros(),
                         EndedPayload{*model.stopped_at, EndKind::kStopped, ""}));
  }
}

void Receiver::CloseSilent() {
  const auto now = std::chrono::steady_clock::now();
  const auto silence = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(options_.sim_silence));
  for (auto& [simulation, clock] : clocks_) {
    if (ended_.count(simulation) > 0 || models_.count(simulation) == 0) continue;
    if (now - clock.heard < silence) continue;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", options_.sim_silence);
    const std::string reason = std::string(kSilentReasonStart) + "no SIM_STATE or SIM_STATUS for " +
                               seconds + " s and no RUN_STOPPED (last step seen " +
                               std::to_string(clock.step) + ")";
    MarkEnded(simulation);
    clock.closed_silent = true;
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.simulations_silent;
    }
    reporter_->Say("bus simulation " + std::to_string(simulation) + ": " + reason +
                   "; closing it (it is reopened if the sim is heard again)");
    Push(MakeEndedRecord(simulation, WallMicros(), EndedPayload{clock.step, EndKind::kSilent, reason}));
  }
}

void Receiver::MarkEnded(int64_t simulation) {
  ended_.insert(simulation);
  follower_.Ended(simulation);
  std::lock_guard<std::mutex> lock(stats_mutex_);
  if (simulation == stats_.simulation_id) stats_.followed_ended = true;
}

void Receiver::Heard(int64_t simulation) {
  SimClock& clock = clocks_[simulation];
  const auto now = std::chrono::steady_clock::now();
  if (clock.closed_silent) {
    // Stopped, not dead (SIGSTOP, a debugger, a link down): the close was
    // wrong, so it is undone, and the silence becomes a gap.
    clock.closed_silent = false;
    clock.silence_after_step = clock.step;
    clock.silence_seconds = std::chrono::duration<double>(now - clock.heard).count();
    ended_.erase(simulation);
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      --stats_.simulations_silent;
      ++stats_.simulations_reopened;
      if (simulation == stats_.simulation_id) stats_.followed_ended = false;
    }
    char text[160];
    std::snprintf(text, sizeof text,
                  "the sim was heard again after %.1f s of silence (last step seen %lld)",
                  clock.silence_seconds, static_cast<long long>(clock.step));
    reporter_->Say("bus simulation " + std::to_string(simulation) + ": " + text + "; reopening it");
    Push(MakeReopenedRecord(simulation, WallMicros(), text));
  }
  clock.heard = now;
}

void Receiver::PushSilenceGap(const state_t& state, const ModelShape& shape) {
  SimClock& clock = clocks_[state.simulation_id];
  const int64_t before = clock.silence_after_step;
  if (before < 0) return;
  clock.silence_after_step = -1;
  if (state.step <= before) return;
  // Logged steps (multiples of the stride) strictly between the two: those
  // lost while the link was down; none if the sim was stopped.
  const int64_t stride = std::lcm<int64_t>(shape.state_every, options_.log_interval);
  const int64_t missing = (state.step - 1) / stride - before / stride;
  char reason[200];
  std::snprintf(reason, sizeof reason,
                "the sim was silent for %.1f s (no SIM_STATE or SIM_STATUS): closed as silent "
                "after %g s, reopened when heard again",
                clock.silence_seconds, options_.sim_silence);
  Push(MakeGapRecord(state.simulation_id, WallMicros(), GapPayload{before, state.step, missing, reason}));
}

std::string Receiver::CheckStepRate(const state_t& s, int64_t received_us, const ModelShape& shape) {
  SimClock& clock = clocks_[s.simulation_id];
  if (clock.step >= 0 && s.step > clock.step) {
    const int64_t elapsed = received_us - clock.received_us;
    const int64_t allowed = StepAllowance(shape.step_size, elapsed, clock.speed_allowance);
    if (s.step - clock.step > allowed) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "step = %lld is %lld steps after step %lld, which came %.3f s earlier: more "
                    "than %g x real time allows (at most %lld steps of %g s); refused as forged "
                    "or absurd",
                    static_cast<long long>(s.step), static_cast<long long>(s.step - clock.step),
                    static_cast<long long>(clock.step), static_cast<double>(elapsed) / 1e6,
                    clock.speed_allowance, static_cast<long long>(allowed), shape.step_size);
      return text;
    }
  }
  if (s.step > clock.step) {
    clock.step = s.step;
    clock.received_us = received_us;
  }
  return "";
}

void Receiver::CheckConflict(const state_t& s, const Record& record) {
  const StateConflicts::Verdict verdict =
      conflicts_.Check(s.simulation_id, s.step, record.payload, StateConflicts::Clock::now());
  if (!verdict.conflict) return;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.state_conflicts;
  }
  if (verdict.line) reporter_->Say(*verdict.line);
}

void Receiver::Deliver(Record record, const state_t* decoded) {
  const auto model = models_.find(record.simulation_id);
  if (model == models_.end()) {
    Wait(std::move(record));
    return;
  }
  const ModelShape& shape = model->second;
  // The checks that need the model.
  if (record.kind == RecordKind::kState) {
    state_t waited;
    if (decoded == nullptr) {
      // A record that waited for its model: decoded once already when it
      // came, so this cannot fail unless memory was damaged.
      if (const auto failure = DecodeLcm(record.payload.data(), record.payload.size(), &waited)) {
        Invalid(channels::kState, DescribeRefusal(channels::kState, state_t::getTypeName(),
                                                  record.payload.size(), *failure));
        return;
      }
      decoded = &waited;
    }
    const state_t& s = *decoded;
    std::string problem;
    if (auto bad = CheckState(s, &shape.outline)) problem = bad->message;
    if (problem.empty()) problem = CheckStepRate(s, record.received_us, shape);
    if (!problem.empty()) {
      Invalid(channels::kState, problem);
      return;
    }
    CheckConflict(s, record);
    PushSilenceGap(s, shape);
    const int64_t step = s.step;
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      if (s.simulation_id == stats_.simulation_id) {
        stats_.last_step = s.step;
        stats_.last_publish_us = s.utime;
        stats_.newest_stamp_us = std::max(stats_.newest_stamp_us, s.utime);
      }
      if (s.step % options_.log_interval != 0) {
        ++stats_.states_skipped;
        return;
      }
    }
    Push(std::move(record), step);
    return;
  } else if (record.kind == RecordKind::kSensor) {
    sensor_reading_t r;
    std::string problem;
    if (const auto failure = DecodeLcm(record.payload.data(), record.payload.size(), &r))
      problem = DescribeRefusal(channels::kSensor, sensor_reading_t::getTypeName(),
                                record.payload.size(), *failure);
    else if (auto bad = CheckSensorReading(r, &shape.outline))
      problem = bad->message;
    if (!problem.empty()) {
      Invalid(channels::kSensor, problem);
      return;
    }
  }
  Push(std::move(record));
}

void Receiver::OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  model_t model;
  if (!Decode(buffer, channel, &model)) return;
  if (const auto problem = CheckModel(model)) {
    Invalid(channel, "model of simulation " + std::to_string(model.simulation_id) + ": " +
                         problem->message);
    return;
  }
  const ModelShape shape = ShapeOf(model);
  const auto known = models_.find(model.simulation_id);
  if (known != models_.end()) {
    const ModelOutline& k = known->second.outline;
    const ModelOutline& now = shape.outline;
    if (k.bodies != now.bodies || k.joints != now.joints || k.sensors.size() != now.sensors.size())
      Invalid(channel, "model of simulation " + std::to_string(model.simulation_id) +
                           " changed its shape (" + std::to_string(now.bodies) + " bodies, " +
                           std::to_string(now.joints) + " joints, " +
                           std::to_string(now.sensors.size()) + " sensors instead of " +
                           std::to_string(k.bodies) + ", " + std::to_string(k.joints) + ", " +
                           std::to_string(k.sensors.size()) + ")");
    return;  // announced again
  }
  const auto now = std::chrono::steady_clock::now();
  if (follower_.OnModel(model.simulation_id, now) ==
      SimulationFollower::Verdict::kOther) {
    SetAside(model, MakeRecord(RecordKind::kModel, model.simulation_id, buffer));
    return;
  }
  Follow(model.simulation_id, shape, MakeRecord(RecordKind::kModel, model.simulation_id, buffer));
}

void Receiver::SetAside(const model_t& model, Record record) {
  const bool is_new = set_aside_.count(model.simulation_id) == 0;
  SetAsideModel& aside = set_aside_[model.simulation_id];  // keeps a stop heard before
  aside.shape = ShapeOf(model);
  aside.record = std::move(record);
  // Only the ones the follower still remembers, and a few: a successor
  // without its model here is asked for it.
  for (auto it = set_aside_.begin(); it != set_aside_.end();)
    it = follower_.IsOther(it->first) ? std::next(it) : set_aside_.erase(it);
  while (set_aside_.size() > kMaxSetAside) set_aside_.erase(set_aside_.begin());
  if (!is_new) return;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.other_simulations;
  }
  reporter_->SayLimited(
      "other simulation",
      "another simulation on the bus: id " + std::to_string(model.simulation_id) + " from '" +
          model.sender + "' (world '" + model.world_name + "'), while simulation " +
          std::to_string(follower_.followed()) +
          " runs: not logged, and it closes nothing (it is logged if the followed sim stops or "
          "goes silent, as a restarted sim would); one bus per sim");
}

void Receiver::Follow(int64_t simulation, const ModelShape& shape, Record model_record) {
  models_[simulation] = shape;
  clocks_[simulation].heard = std::chrono::steady_clock::now();
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.simulation_id = simulation;
    stats_.last_step = -1;
    stats_.newest_stamp_us = 0;
    stats_.followed_ended = ended_.count(simulation) > 0;
  }
  Push(std::move(model_record));
  DeliverWaiting(simulation);
}

void Receiver::DeliverWaiting(int64_t simulation) {
  // What waited for this model, in arrival order; commands sent before any
  // model belong to the first simulation.
  std::deque<Record> still_waiting;
  std::deque<Record> ready;
  for (Record& r : waiting_) {
    if (r.simulation_id == simulation ||
        (r.kind == RecordKind::kCommand && r.simulation_id == 0)) {
      r.simulation_id = simulation;
      ready.push_back(std::move(r));
    } else {
      still_waiting.push_back(std::move(r));
    }
  }
  waiting_ = std::move(still_waiting);
  waiting_bytes_ = 0;
  for (const Record& r : waiting_) waiting_bytes_ += r.ByteSize();
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.waiting = waiting_.size();
  }
  for (Record& r : ready) Deliver(std::move(r));
}

void Receiver::OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  state_t state;
  if (!Decode(buffer, channel, &state)) return;
  follower_.Heard(state.simulation_id, std::chrono::steady_clock::now());
  if (models_.count(state.simulation_id) > 0) Heard(state.simulation_id);
  Deliver(MakeRecord(RecordKind::kState, state.simulation_id, buffer), &state);
}

void Receiver::OnSensor(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  sensor_reading_t reading;
  if (!Decode(buffer, channel, &reading)) return;
  Deliver(MakeRecord(RecordKind::kSensor, reading.simulation_id, buffer));
}

void Receiver::OnCommand(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  command_t command;
  if (!Decode(buffer, channel, &command)) return;
  if (const auto problem = CheckCommand(command)) {
    Invalid(channel, problem->message);
    return;
  }
  // Logged under the simulation it was meant for when the logger knows
  // it, else (0 = any, or one never seen) under the one followed.
  int64_t simulation = command.simulation_id;
  if (simulation == 0 || models_.count(simulation) == 0) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    simulation = stats_.simulation_id;
  }
  Deliver(MakeRecord(RecordKind::kCommand, simulation, buffer));
}

void Receiver::OnReply(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  command_reply_t reply;
  if (!Decode(buffer, channel, &reply)) return;
  if (const auto problem = CheckCommandReply(reply)) {
    Invalid(channel, problem->message);
    return;
  }
  Deliver(MakeRecord(RecordKind::kCommandReply, reply.simulation_id, buffer));
}

void Receiver::OnStatus(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  status_t status;
  if (!Decode(buffer, channel, &status)) return;
  if (const auto problem = CheckStatus(status)) {
    Invalid(channel, problem->message);
    return;
  }
  follower_.Heard(status.simulation_id, std::chrono::steady_clock::now());
  if (const auto aside = set_aside_.find(status.simulation_id);
      aside != set_aside_.end() && status.run_state == status_t::RUN_STOPPED)
    aside->second.stopped_at = status.step;  // closed when followed
  if (models_.count(status.simulation_id) == 0) return;
  Heard(status.simulation_id);
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    if (status.simulation_id == stats_.simulation_id)
      stats_.newest_stamp_us = std::max(stats_.newest_stamp_us, status.utime);
  }
  clocks_[status.simulation_id].speed_allowance =
      SpeedAllowance(status.target_speed, status.real_time_factor);
  // Reset: the next model is its successor's, which closes this one.
  if (status.run_state == status_t::RUN_RESET) follower_.Ended(status.simulation_id);
  if (status.run_state != status_t::RUN_STOPPED) return;
  if (ended_.count(status.simulation_id) > 0) return;
  MarkEnded(status.simulation_id);
  Push(MakeEndedRecord(status.simulation_id, WallMicros(),
                       EndedPayload{status.step, EndKind::kStopped, ""}));
}

ReceiverStats Receiver::Stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

}  // namespace simpartner::logger
