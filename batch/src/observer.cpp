#include "observer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "simpartner/channels.h"
#include "simpartner/random_token.h"
#include "simpartner/sender.h"
#include "simpartner/state_request_t.hpp"
#include "simpartner/sync_t.hpp"

namespace simpartner::batch {

RunObserver::RunObserver(const std::string& url, const std::vector<Figure>& figures)
    : lcm_(url),
      url_(url),
      figures_(figures),
      accumulators_(figures.size()),
      sender_(SenderName("simpartner-batch")) {
  signing_ = BusSigning::FromEnvironment({});  // the batch said at start which key
  if (!lcm_.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
  lcm_.subscribe(channels::kModel, &RunObserver::OnModel, this);
  lcm_.subscribe(channels::kState, &RunObserver::OnState, this)->setQueueCapacity(100000);
  lcm_.subscribe(channels::kStateReply, &RunObserver::OnStateReply, this);
  lcm_.subscribe(channels::kSyncReply, &RunObserver::OnSyncReply, this);
}

void RunObserver::Pump(int quiet_ms, int budget_ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(budget_ms);
  // handleTimeout dispatches one message: go on while they come.
  int handled;
  while ((handled = lcm_.handleTimeout(quiet_ms)) > 0) {
    last_heard_ = std::chrono::steady_clock::now();
    if (last_heard_ >= end) return;
  }
  // LCM opens its receiving socket on the first handle: a port held by a
  // socket without SO_REUSEADDR makes it fail, and the bus deaf.
  if (handled < 0) throw std::runtime_error("cannot receive on '" + url_ + "' (LCM said why above)");
  AskAgainIfQuiet();
}

void RunObserver::PublishMark(int8_t action, int64_t period, int64_t tick) {
  sync_t mark{};
  mark.utime = WallMicros();
  mark.controller = kPaceName;
  mark.sender = sender_;
  if (action == sync_t::ACTION_JOIN && join_nonce_.empty()) join_nonce_ = RandomToken();
  mark.token = action == sync_t::ACTION_JOIN ? join_nonce_ : token_;
  mark.action = action;
  mark.period = period;
  mark.tick = tick;
  PublishSigned(&lcm_, channels::kSync, mark, signer());
}

void RunObserver::AskToJoin() { PublishMark(sync_t::ACTION_JOIN, kPacePeriod, 0); }

void RunObserver::Answer(int64_t tick) {
  PublishMark(sync_t::ACTION_DONE, 0, tick);
  answered_ = std::max(answered_, tick);
}

// Quiet while paced: the sim may wait at a tick whose state was lost, or
// for an answer that was; it says which step it is at (OnStateReply). A
// paused sim answers too, at most a few times a second.
void RunObserver::AskAgainIfQuiet() {
  if (!joined() || !pacing_ ||
      std::chrono::steady_clock::now() - last_heard_ < std::chrono::milliseconds(200))
    return;
  state_request_t request{};
  request.utime = WallMicros();
  request.sender = sender_;
  PublishSigned(&lcm_, channels::kStateRequest, request, signer());
  last_heard_ = std::chrono::steady_clock::now();
}

void RunObserver::OnStateReply(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  state_t state;
  if (DecodeSigned(channel, buffer->data, buffer->data_size, signer(), &state, &refused_)) return;
  if (!joined() || !pacing_ || (model_ && state.simulation_id != model_->simulation_id)) return;
  // The sim waits at this step: for our answer to a tick whose state we
  // missed (the stream then has a gap, and the hash says so), or for an
  // answer of ours that was lost (sent again; refused as a duplicate if not).
  if (state.step >= first_tick_ && state.step % kPacePeriod == 0) Answer(state.step);
}

void RunObserver::OnSyncReply(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  sync_reply_t reply;
  if (DecodeSigned(channel, buffer->data, buffer->data_size, signer(), &reply, &refused_)) return;
  if (reply.controller != kPaceName || reply.sender != sender_) return;
  // Replies to marks forged in its name echo another token (sync_reply_t.lcm).
  if (reply.event != sync_reply_t::EVENT_JOINED &&
      !SameToken(reply.token, token_.empty() ? join_nonce_ : token_))
    return;
  if (reply.event == sync_reply_t::EVENT_JOINED) {
    first_tick_ = reply.tick;
    token_ = reply.token;
  } else if (reply.event == sync_reply_t::EVENT_RELEASED ||
             (reply.event == sync_reply_t::EVENT_REFUSED &&
              reply.reason.find("duplicate") == std::string::npos)) {
    pacing_ = false;  // the run goes on unpaced
    pace_problem_ = reply.reason;
  }
}

void RunObserver::OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  model_t model;
  if (DecodeSigned(channel, buffer->data, buffer->data_size, signer(), &model, &refused_)) return;
  if (model_) return;  // the periodic announcement of the same model
  if (const auto problem = CheckModel(model)) {
    refused_.Count(channel, problem->message);
    return;
  }
  outline_ = OutlineOf(model);
  for (size_t f = 0; f < figures_.size(); ++f)
    for (const body_t& b : model.bodies)
      if (b.name == figures_[f].body && accumulators_[f].body < 0) accumulators_[f].body = b.id;
  model_ = std::move(model);
}

void RunObserver::OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  state_t state;
  if (DecodeSigned(channel, buffer->data, buffer->data_size, signer(), &state, &refused_)) return;
  if (model_ && state.simulation_id != model_->simulation_id) return;
  // A state not taken is a gap in the stream, as a lost one is.
  if (const auto problem = CheckState(state, model_ ? &outline_ : nullptr)) {
    refused_.Count(channel, problem->message);
    return;
  }
  // Every step, in order (the sim publishes each, stateEvery 1): a gap or
  // a step out of order makes the hash no longer the run's.
  if (state.step != last_step_ + 1 && !(last_step_ < 0 && state.step == 1)) complete_ = false;
  last_step_ = state.step;
  sim_time_ = state.sim_time;
  ++states_;
  state_t copy = state;
  copy.utime = 0;
  copy.simulation_id = 0;
  std::vector<uint8_t> bytes(static_cast<size_t>(copy.getEncodedSize()));
  copy.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  for (const uint8_t byte : bytes) hash_ = (hash_ ^ byte) * 1099511628211ull;
  Accumulate(state);
  if (joined() && pacing_ && state.step >= first_tick_ && state.step % kPacePeriod == 0)
    Answer(state.step);
}

void RunObserver::Accumulate(const state_t& state) {
  for (Accumulator& a : accumulators_) {
    if (a.body < 0 || static_cast<size_t>(a.body) >= state.bodies.size()) continue;
    const body_state_t& b = state.bodies[static_cast<size_t>(a.body)];
    if (a.any)
      a.path += std::hypot(b.position[0] - a.position[0], b.position[1] - a.position[1],
                           b.position[2] - a.position[2]);
    for (int k = 0; k < 3; ++k) a.position[k] = b.position[k];
    a.speed = std::hypot(b.linear_velocity[0], b.linear_velocity[1], b.linear_velocity[2]);
    a.peak_force = std::max(a.peak_force, std::hypot(b.contact_force[0], b.contact_force[1],
                                                     b.contact_force[2]));
    a.any = true;
  }
}

std::string RunObserver::Hash(int64_t last_step) const {
  if (!complete_ || states_ == 0 || last_step_ != last_step) return "";
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
  return text;
}

std::vector<double> RunObserver::Figures() const {
  std::vector<double> values;
  for (size_t f = 0; f < figures_.size(); ++f) {
    const Accumulator& a = accumulators_[f];
    if (!a.any) {
      values.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    switch (figures_[f].quantity) {
      case Quantity::kX: values.push_back(a.position[0]); break;
      case Quantity::kY: values.push_back(a.position[1]); break;
      case Quantity::kZ: values.push_back(a.position[2]); break;
      case Quantity::kPathLength: values.push_back(a.path); break;
      case Quantity::kFinalSpeed: values.push_back(a.speed); break;
      case Quantity::kPeakContactForce: values.push_back(a.peak_force); break;
    }
  }
  return values;
}

}  // namespace simpartner::batch
